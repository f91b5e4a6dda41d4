// bench-axial-dynamics: AxialDynamics::QuasiStatic against the paper's Dynamic axial modes on the
// default demo case (Table 1 pendulum, 1 m/s push, 20 s), for several n_a.
//
// For each n_a and each model a converged reference is integrated (RK-Merson at --accuracy, checked
// against a run at 10x that accuracy) and sampled every --sample s: payload centre, axial force at
// the payload end of the vertical span (P = EA eps at s = L, the paper's Fig 4 quantity) and the
// force the rope puts on the payload (getNodeForce). Each force series is split into a slow part (a
// zero-phase Gaussian low-pass with its -3 dB point at --cutoff Hz, default 10 x the 4.3 Hz bounce)
// and the rest (the axial-wave part). Writes DIR/summary.md, DIR/series_na<N>.csv and gnuplot
// figures DIR/axial_dynamics_na<N>.png.
//
// Reproduce: build/bench/bench-axial-dynamics --out out/axial-dynamics   (docs/verification.md)
#include <SimbodyReeving/simbody/Integrators.h>
#include <SimbodyReeving/simbody/InterpolatingTimeStepper.h>
#include <SimbodyReeving/scenes/PendulumScene.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace SimbodyReeving;

namespace {

struct Series {
    std::vector<double> t, x, y, P, F;  // F: vertical component of the rope force on the payload [N]
    double wall = 0;
    long steps = 0;
};

Series simulate(int na, AxialDynamics axial, double accuracy, double tEnd, double sample) {
    SpanOptions o;
    o.axialModes = na;
    o.transverseModes = 1;
    o.axialDynamics = axial;
    o.velocityModel = VelocityModel::Simplified;  // not the default: the setting of the recorded results
    const PendulumScene scene(PendulumParameters{}, o);
    SimTK::State s = scene.makeInitialState(1.0, 0.0);
    auto integ = makeIntegrator("rk-merson", scene.system());
    integ->setAccuracy(accuracy);
    InterpolatingTimeStepper ts(scene.system(), *integ);
    ts.initialize(s);
    Series out;
    const auto start = std::chrono::steady_clock::now();
    const int n = static_cast<int>(std::lround(tEnd / sample));
    for (int k = 0; k <= n; ++k) {
        if (k > 0) ts.stepTo(k * sample);
        const SimTK::State& st = ts.getState();
        scene.system().realize(st, SimTK::Stage::Dynamics);
        const SimTK::Vec3 p = scene.payloadPosition(st);
        out.t.push_back(st.getTime());
        out.x.push_back(p[0]);
        out.y.push_back(p[1]);
        out.P.push_back(scene.axialForceAtPayload(st));
        out.F.push_back(scene.reeving().getNodeForce(st, 0, 2)[1]);
    }
    out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.steps = integ->getNumStepsTaken();
    return out;
}

/// Zero-phase Gaussian low-pass: sigma = sqrt(ln 2) / (2 pi fc) puts the -3 dB point at fc; the
/// kernel is truncated at 4 sigma and renormalised near the ends of the record.
std::vector<double> lowPass(const std::vector<double>& v, double dt, double fc) {
    const double sigma = std::sqrt(std::log(2.0)) / (2.0 * M_PI * fc);
    const int half = static_cast<int>(std::ceil(4.0 * sigma / dt));
    std::vector<double> w(2 * half + 1);
    for (int k = -half; k <= half; ++k) w[k + half] = std::exp(-0.5 * std::pow(k * dt / sigma, 2));
    std::vector<double> out(v.size());
    const int n = static_cast<int>(v.size());
    for (int i = 0; i < n; ++i) {
        double sum = 0, norm = 0;
        for (int k = -half; k <= half; ++k) {
            const int j = i + k;
            if (j < 0 || j >= n) continue;
            sum += w[k + half] * v[j];
            norm += w[k + half];
        }
        out[i] = sum / norm;
    }
    return out;
}

// Statistics skip the first and last `gEdge` samples, where the low-pass kernel is truncated.
size_t gEdge = 0;

double maxAbsDiff(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (size_t i = gEdge; i + gEdge < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
    return m;
}
double maxPositionDiff(const Series& a, const Series& b) {
    double m = 0;
    for (size_t i = 0; i < a.t.size(); ++i) m = std::max(m, std::hypot(a.x[i] - b.x[i], a.y[i] - b.y[i]));
    return m;
}
double maxAbs(const std::vector<double>& a) {
    double m = 0;
    for (size_t i = gEdge; i + gEdge < a.size(); ++i) m = std::max(m, std::abs(a[i]));
    return m;
}
std::vector<double> minus(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> r(a.size());
    for (size_t i = 0; i < a.size(); ++i) r[i] = a[i] - b[i];
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> modes{1, 3, 8};
    double accuracy = 1e-8, tEnd = 20, sample = 1e-3, cutoff = 43.0;
    std::string outDir = "out/axial-dynamics";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::cerr << "bench-axial-dynamics: " << a << ": missing value\n";
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--axial-modes") {
            modes.clear();
            std::stringstream ss(next());
            std::string item;
            while (std::getline(ss, item, ',')) modes.push_back(std::stoi(item));
        } else if (a == "--accuracy") {
            accuracy = std::stod(next());
        } else if (a == "--t-end") {
            tEnd = std::stod(next());
        } else if (a == "--sample") {
            sample = std::stod(next());
        } else if (a == "--cutoff") {
            cutoff = std::stod(next());
        } else if (a == "--out") {
            outDir = next();
        } else {
            std::cerr << "usage: bench-axial-dynamics [--axial-modes 1,3,8] [--accuracy 1e-8] [--t-end 20] "
                         "[--sample 1e-3] [--cutoff 43] [--out DIR]\n";
            return a == "--help" ? 0 : 2;
        }
    }
    fs::create_directories(outDir);
    gEdge = static_cast<size_t>(std::ceil(4.0 * std::sqrt(std::log(2.0)) / (2.0 * M_PI * cutoff) / sample));
    std::ofstream md(fs::path(outDir) / "summary.md");
    md << "Default demo case (Table 1, 1 m/s push, " << tEnd << " s), RK-Merson " << accuracy
       << " (reference check at " << accuracy / 10 << "), sampled every " << sample << " s; slow part = Gaussian low-pass, -3 dB at "
       << cutoff << " Hz; maxima over the record less 4 sigma of the filter at each end.\n\n"
       << "| n_a | max payload position difference [m] | max end-force difference P [N] | slow part [N] | "
          "axial-wave part of the difference [N] | slow part of node force difference [N] | "
          "reference check Dynamic (pos m / P N) | reference check QuasiStatic (pos m / P N) | wall Dynamic / QuasiStatic [s] | steps Dynamic / QuasiStatic |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (int na : modes) {
        std::fprintf(stderr, "n_a = %d ...\n", na);
        const Series d = simulate(na, AxialDynamics::Dynamic, accuracy, tEnd, sample);
        const Series d2 = simulate(na, AxialDynamics::Dynamic, accuracy / 10, tEnd, sample);
        const Series q = simulate(na, AxialDynamics::QuasiStatic, accuracy, tEnd, sample);
        const Series q2 = simulate(na, AxialDynamics::QuasiStatic, accuracy / 10, tEnd, sample);
        const std::vector<double> dSlow = lowPass(d.P, sample, cutoff), qSlow = lowPass(q.P, sample, cutoff);
        const std::vector<double> dFSlow = lowPass(d.F, sample, cutoff), qFSlow = lowPass(q.F, sample, cutoff);
        const double pos = maxPositionDiff(d, q), dP = maxAbsDiff(d.P, q.P), dPslow = maxAbsDiff(dSlow, qSlow);
        // Axial-wave part: what the low-pass removes from the difference (the fast part of P_d - P_q).
        const double wave = maxAbs(minus(minus(d.P, dSlow), minus(q.P, qSlow))), dFslow = maxAbsDiff(dFSlow, qFSlow);
        char row[1024];
        std::snprintf(row, sizeof row,
                      "| %d | %.2e | %.3f | %.4f | %.3f | %.4f | %.1e / %.1e | %.1e / %.1e | %.1f / %.2f | %ld / %ld |\n", na,
                      pos, dP, dPslow, wave, dFslow, maxPositionDiff(d, d2), maxAbsDiff(d.P, d2.P),
                      maxPositionDiff(q, q2), maxAbsDiff(q.P, q2.P), d.wall, q.wall, d.steps, q.steps);
        md << row;
        md.flush();
        std::fputs(row, stderr);
        const fs::path csv = fs::path(outDir) / ("series_na" + std::to_string(na) + ".csv");
        std::ofstream c(csv);
        c << "t,x_dynamic,y_dynamic,x_quasistatic,y_quasistatic,P_dynamic,P_quasistatic,P_dynamic_slow,P_quasistatic_slow,"
             "F_dynamic,F_quasistatic\n";
        c.precision(12);
        for (size_t i = 0; i < d.t.size(); ++i)
            c << d.t[i] << ',' << d.x[i] << ',' << d.y[i] << ',' << q.x[i] << ',' << q.y[i] << ',' << d.P[i] << ','
              << q.P[i] << ',' << dSlow[i] << ',' << qSlow[i] << ',' << d.F[i] << ',' << q.F[i] << '\n';
        c.close();
        const std::string png = "axial_dynamics_na" + std::to_string(na) + ".png";
        std::ofstream gp(fs::path(outDir) / ("plot_na" + std::to_string(na) + ".gp"));
        gp << "set terminal png size 1000,900 font 'DejaVu Sans,10'\nset output '" << png
           << "'\nset datafile separator ','\nset grid\nset multiplot layout 3,1 title 'n_a = " << na
           << ": QuasiStatic vs Dynamic axial modes (Table 1 pendulum, 1 m/s push)'\n"
           << "set ylabel 'P at payload end [N]'\nplot '" << csv.filename().string()
           << "' every ::1 using 1:6 with lines lw 1 lc rgb '#bbbbbb' title 'Dynamic', '' every ::1 using 1:8 with lines lw 2 "
              "title 'Dynamic, slow part', '' every ::1 using 1:7 with lines lw 1 dt 2 title 'QuasiStatic'\n"
           << "set ylabel 'P difference [N]'\nplot '' every ::1 using 1:($7-$6) with lines lc rgb '#bbbbbb' title "
              "'QuasiStatic - Dynamic', '' every ::1 using 1:($9-$8) with lines lw 2 title 'slow parts'\n"
           << "set ylabel 'payload position difference [m]'\nset xlabel 't [s]'\nplot '' every ::1 using 1:($4-$2) with "
              "lines title 'x', '' every ::1 using 1:($5-$3) with lines title 'y'\nunset multiplot\n";
        gp.close();
        const std::string cmd = "cd '" + outDir + "' && gnuplot plot_na" + std::to_string(na) + ".gp";
        if (std::system(cmd.c_str()) != 0) std::cerr << "bench-axial-dynamics: gnuplot failed for n_a = " << na << "\n";
    }
    std::cerr << "written: " << (fs::path(outDir) / "summary.md").string() << "\n";
    return 0;
}
