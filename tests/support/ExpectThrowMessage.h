#pragma once
// Error tests that check what the user reads: the exception's exact type and the words of its message.
//
//   EXPECT_THROW_MESSAGE(statement, ExceptionType, "words");
//   ASSERT_THROW_MESSAGE(statement, ExceptionType, "words");
//
// pass only if `statement` throws an exception whose dynamic type is exactly ExceptionType (a class
// derived from it fails too: the test names the type the library documents) and whose what()
// contains "words" (case-sensitive substring). On failure they print the statement, the expected
// type and words, and what actually happened: nothing thrown, or the thrown type and its message.
// EXPECT_ continues the test, ASSERT_ returns from the current function. The statement is run in a
// lambda that captures by reference; like EXPECT_THROW, a top-level comma needs parentheses.
//
// gtest only (no Eigen, no Simbody): usable by the element layer's tests and the Simbody layer's.

#include <gtest/gtest.h>

#include <exception>
#include <string>
#include <type_traits>
#include <typeinfo>

#if defined(__GNUG__)
#include <cxxabi.h>

#include <cstdlib>
#include <memory>
#endif

namespace SimbodyReeving::test {

/// The readable name of a type (demangled where the compiler allows).
inline std::string readableTypeName(const std::type_info& type) {
#if defined(__GNUG__)
    int status = 0;
    const std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(type.name(), nullptr, nullptr, &status),
                                                      std::free);
    if (status == 0 && name) return name.get();
#endif
    return type.name();
}

/// Runs `statement`; success if it throws exactly ExceptionType with `words` in its what().
template <class ExceptionType, class Statement>
::testing::AssertionResult throwsWithMessage(Statement&& statement, const char* statementText,
                                             const char* expectedTypeText, const std::string& words) {
    static_assert(!std::is_same_v<ExceptionType, std::exception>, "name the exact exception type the library throws");
    const auto expected = [&] {
        return std::string("Expected: ") + statementText + " throws " + expectedTypeText +
               " with a message containing \"" + words + "\"\n  Actual: ";
    };
    try {
        statement();
    } catch (const ExceptionType& e) {
        const std::string thrownType = readableTypeName(typeid(e));
        const std::string message = e.what();
        if (typeid(e) != typeid(ExceptionType))
            return ::testing::AssertionFailure()
                   << expected() << "it throws " << thrownType << " (derived from " << expectedTypeText
                   << "; name the exact type) with message \"" << message << "\"";
        if (message.find(words) == std::string::npos)
            return ::testing::AssertionFailure()
                   << expected() << "it throws " << thrownType << " with message \"" << message << "\"";
        return ::testing::AssertionSuccess();
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << expected() << "it throws " << readableTypeName(typeid(e))
                                             << " with message \"" << e.what() << "\"";
    } catch (...) {
        return ::testing::AssertionFailure() << expected() << "it throws an exception not derived from std::exception";
    }
    return ::testing::AssertionFailure() << expected() << "it throws nothing";
}

}  // namespace SimbodyReeving::test

#define SIMBODYREEVING_THROW_MESSAGE_(statement, ExceptionType, words, on_failure)                                  \
    do {                                                                                                           \
        const ::testing::AssertionResult simbodyreeving_throw_result_ =                                            \
            ::SimbodyReeving::test::throwsWithMessage<ExceptionType>([&]() { statement; }, #statement,              \
                                                                     #ExceptionType, words);                        \
        if (!simbodyreeving_throw_result_) on_failure() << simbodyreeving_throw_result_.message();                \
    } while (false)

/// Fails the test (and continues) unless `statement` throws exactly ExceptionType whose what()
/// contains `words`.
#define EXPECT_THROW_MESSAGE(statement, ExceptionType, words) \
    SIMBODYREEVING_THROW_MESSAGE_(statement, ExceptionType, words, ADD_FAILURE)

/// As EXPECT_THROW_MESSAGE, and returns from the current function on failure.
#define ASSERT_THROW_MESSAGE(statement, ExceptionType, words) \
    SIMBODYREEVING_THROW_MESSAGE_(statement, ExceptionType, words, FAIL)
