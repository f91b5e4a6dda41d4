// docs/studies.md against the programs: the runner's options as its --help lists them, and the
// study file of "The study file" a study that the crane demo accepts.
#include "StudyTestSupport.h"

#include "Cases.h"
#include "StudyFile.h"

#include <regex>
#include <set>

using namespace study_test;

namespace {

const std::string kStudy = REEVING_STUDY_EXE;
const std::string kCrane = REEVING_CRANE_EXE;
const fs::path kDocs = STUDY_DOCS_FILE;

// The long options (--name) in a text.
std::set<std::string> longOptions(const std::string& text) {
    std::set<std::string> names;
    const std::regex option("--[a-z][a-z-]*");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it)
        names.insert(it->str());
    return names;
}

// The first fenced block of `language` after the heading `heading` in the docs whose text starts
// with `start`.
std::string block(const std::string& heading, const std::string& language, const std::string& start = "") {
    const std::vector<std::string> all = lines(kDocs);
    auto at = std::find(all.begin(), all.end(), heading);
    EXPECT_NE(at, all.end()) << "no heading '" << heading << "' in " << kDocs;
    while (at != all.end()) {
        at = std::find_if(at, all.end(), [](const std::string& line) { return line.rfind("```", 0) == 0; });
        if (at == all.end()) break;
        const std::string opening = *at;
        std::string text;
        for (++at; at != all.end() && *at != "```"; ++at) text += *at + "\n";
        if (at != all.end()) ++at;
        if (opening == "```" + language && text.rfind(start, 0) == 0) return text;
    }
    ADD_FAILURE() << "no ```" << language << " block starting '" << start << "' after '" << heading << "'";
    return "";
}

}  // namespace

// The synopsis and the bullet list under "Running a study" name exactly the options of
// `reeving-study --help` (but --help).
TEST(StudyDocs, RunnerOptionsAreThoseOfItsHelp) {
    const fs::path dir = scratch("docs-options");
    const ProgramRun r = run(quote(kStudy) + " --help", dir);
    ASSERT_EQ(r.status, 0) << r.err;
    std::set<std::string> help;
    for (std::istringstream in(r.out); !in.eof();) {
        std::string line;
        std::getline(in, line);
        if (line.rfind("  -", 0) == 0) help.merge(longOptions(line.substr(0, line.find("  ", 2))));
    }
    EXPECT_EQ(help, (std::set<std::string>{"--help", "--out", "--dry-run", "--resume", "--quiet", "--demo-dir"}));
    help.erase("--help");
    const std::string synopsis = block("## Running a study", "", "reeving-study STUDY ");
    EXPECT_EQ(longOptions(synopsis), help) << synopsis;
    std::set<std::string> bullets;
    for (const std::string& line : lines(kDocs))
        if (line.rfind("- `--", 0) == 0) bullets.insert(line.substr(3, line.find_first_of(" `", 3) - 3));
    EXPECT_EQ(bullets, help);
}

// The example study file reads, makes the cases the text says (2 x 5 x 4 grid points x 10 samples),
// and its first and last cases pass reeving-crane --check: every parameter it uses is an option
// of the crane demo (reeving-crane --help), every value in range.
TEST(StudyDocs, TheExampleStudyFileIsACraneStudy) {
    const fs::path dir = scratch("docs-example");
    const std::string text = block("## The study file", "yaml");
    study::Study s;
    ASSERT_NO_THROW(s = study::parseStudy(text, "studies.md.yaml"));
    EXPECT_EQ(s.scene->name, "crane");
    const std::vector<study::Case> cases = study::makeCases(s);
    ASSERT_EQ(cases.size(), 400u);
    for (const study::Case* c : {&cases.front(), &cases.back()}) {
        std::string command = quote(kCrane) + " --check";
        for (const std::string& a : study::demoArguments(s, *c, (dir / "out").string())) command += " '" + a + "'";
        const ProgramRun r = run(command, dir);
        EXPECT_EQ(r.status, 0) << command << "\n" << r.err;
        EXPECT_EQ(r.out + r.err, "") << command;
    }
    EXPECT_FALSE(fs::exists(dir / "out"));
}
