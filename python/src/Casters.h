#pragma once
// SimTK::Vec3 across the boundary: from any sequence of three numbers (a tuple, a list, a numpy
// array), to a numpy array of three floats. Included by every source that casts a Vec3 (one
// definition of the caster for the whole module).

#include <Simbody.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace pybind11 {
namespace detail {

template <>
struct type_caster<SimTK::Vec3> {
public:
    PYBIND11_TYPE_CASTER(SimTK::Vec3, const_name("Vec3"));

    bool load(handle src, bool) {
        if (!src || isinstance<str>(src) || isinstance<bytes>(src) || !isinstance<sequence>(src)) {
            // a numpy array is a sequence too; anything else is not a vector
            if (!src || !isinstance<array>(src)) return false;
        }
        try {
            const sequence seq = reinterpret_borrow<sequence>(src);
            if (seq.size() != 3) return false;
            for (size_t i = 0; i < 3; ++i) {
                object item = seq[i];
                if (!isinstance<float_>(item) && !isinstance<int_>(item) &&
                    !hasattr(item, "__float__"))
                    return false;
                value[static_cast<int>(i)] = item.cast<double>();
            }
            return true;
        } catch (const error_already_set&) {
            PyErr_Clear();
            return false;
        } catch (const cast_error&) {
            return false;
        }
    }

    static handle cast(const SimTK::Vec3& v, return_value_policy, handle) {
        array_t<double> a(3);
        for (int i = 0; i < 3; ++i) a.mutable_data()[i] = v[i];
        return a.release();
    }
};

}  // namespace detail
}  // namespace pybind11
