// Acceptance 8 (the "how you know" part): one span evaluation performs no heap allocation.
// This test binary replaces the global operator new/delete with counting versions; the count over
// repeated evaluate() calls must stay zero for planar and spatial spans, both velocity models and
// both energy models, at the largest mode counts.
#include "SimbodyReeving/SpanModel.h"
#include "support/SpanTestSupport.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> gAllocations{0};
}

void* operator new(std::size_t size) {
    ++gAllocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace SimbodyReeving;

namespace {

template <int Dim>
long allocationsPerEvaluation(int na, int nt, VelocityModel vm, ElasticEnergyModel em) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = nt;
    o.velocityModel = vm;
    o.elasticModel = em;
    Eigen::Matrix<double, Dim, Dim> ref = Eigen::Matrix<double, Dim, Dim>::Identity();
    const SpanModel<Dim> model({0.6, 1e6, 30}, o, Eigen::Matrix<double, Dim, 1>::Constant(-1.0), ref);
    std::mt19937 rng(5);
    const Eigen::VectorXd q = test::randomState(model, rng);
    const Eigen::VectorXd qd = test::randomVelocity(model, rng);
    SpanData<Dim> data;
    model.evaluate(q, qd, data);  // warm-up
    const long before = gAllocations.load();
    for (int k = 0; k < 10; ++k) model.evaluate(q, qd, data);
    return gAllocations.load() - before;
}

}  // namespace

TEST(SpanNoAllocation, CounterSeesAllocations) {
    const long before = gAllocations.load();
    auto* p = new Eigen::VectorXd(100);
    delete p;
    EXPECT_GE(gAllocations.load() - before, 1);  // the counter works
}

TEST(SpanNoAllocation, EvaluateNeverAllocates) {
    for (auto vm : {VelocityModel::Simplified, VelocityModel::Complete})
        for (auto em : {ElasticEnergyModel::Consistent, ElasticEnergyModel::PaperLiteral}) {
            EXPECT_EQ(allocationsPerEvaluation<2>(3, 1, vm, em), 0);
            EXPECT_EQ(allocationsPerEvaluation<3>(3, 1, vm, em), 0);
            EXPECT_EQ(allocationsPerEvaluation<2>(16, 16, vm, em), 0);
            EXPECT_EQ(allocationsPerEvaluation<3>(16, 16, vm, em), 0);
        }
}
