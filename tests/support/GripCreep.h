#pragma once
// The creep of the rope against the groove of a drum that grips it (RopeModel::setGrip),
// integrated by a test from its own samples: the groove carries the rope away at its surface, so
// the material at the tangent point moves at v / lambda where the groove there moves at v, and
// the rope wound on is short of the groove it covers by
//     c = integral of (1 / lambda - 1) dG,
// G the groove length the tangent point has covered [m] (R times its turn on a held drum),
// lambda = sqrt(1 + 2 eps) the stretch there. The samples' trapezoid sums at steps h and 2 h are
// combined by Richardson's rule, I_h + (I_h - I_2h) / 3: fourth order in h for a smooth run.

#include <stdexcept>

namespace SimbodyReevingTest {

class GripCreep {
public:
    /// Starts at the first sample: the stretch lambda and the groove length G there [m].
    GripCreep(double lambda, double groove) : last_{lambda, groove}, pairStart_{lambda, groove} {}
    /// The next sample (equal time steps).
    void add(double lambda, double groove) {
        const Sample now{lambda, groove};
        fine_ += trapezoid(last_, now);
        last_ = now;
        if (++steps_ % 2 == 0) {
            coarse_ += trapezoid(pairStart_, now);
            pairStart_ = now;
        }
    }
    /// True after an even number of steps: value() is the fourth-order estimate.
    bool ready() const { return steps_ % 2 == 0; }
    /// c [m].
    /// @throws std::logic_error after an odd number of steps (the coarse sum is one step short).
    double value() const {
        if (!ready()) throw std::logic_error("GripCreep: the value needs an even number of steps");
        return fine_ + (fine_ - coarse_) / 3;
    }

private:
    struct Sample {
        double lambda, groove;
    };
    static double trapezoid(const Sample& a, const Sample& b) {
        return 0.5 * ((1 / a.lambda - 1) + (1 / b.lambda - 1)) * (b.groove - a.groove);
    }
    Sample last_, pairStart_;
    double fine_ = 0, coarse_ = 0;
    int steps_ = 0;
};

}  // namespace SimbodyReevingTest
