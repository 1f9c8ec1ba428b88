// Timing harness for ruckig's own C++ (an external oracle measurement: not part of shearcut, its
// crates or CI; built and run by scripts/ruckig_cpp_timing.sh against the ruckig 0.19.4 sources
// downloaded from PyPI, never copied into this repository).
//
// Reads the cases written by `otg_vs_ruckig.py --dump-timing-cases FILE` (one case per line:
// the DoF count, then the current position, velocity, acceleration, target position, velocity,
// acceleration, max velocity, max acceleration and max jerk, each a vector of that many values;
// time synchronisation) and prints, per DoF count, the median, p99 and worst time of
// `Ruckig::calculate` (which validates the input itself), timed with std::chrono::steady_clock
// around each call, for the compile-time DoF count and for ruckig's dynamic DoFs (what its
// Python binding uses).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ruckig/ruckig.hpp>

struct Case {
    size_t dofs;
    std::vector<double> v;  // 9 * dofs values
};

template <class Otg, class In, class Traj>
static void run(const char* label, size_t dofs, Otg& otg, In& inp, Traj& traj, const std::vector<Case>& cases) {
    std::vector<double> times;
    size_t errors = 0;
    for (const auto& c : cases) {
        if (c.dofs != dofs) continue;
        for (size_t i = 0; i < dofs; ++i) {
            inp.current_position[i] = c.v[0 * dofs + i];
            inp.current_velocity[i] = c.v[1 * dofs + i];
            inp.current_acceleration[i] = c.v[2 * dofs + i];
            inp.target_position[i] = c.v[3 * dofs + i];
            inp.target_velocity[i] = c.v[4 * dofs + i];
            inp.target_acceleration[i] = c.v[5 * dofs + i];
            inp.max_velocity[i] = c.v[6 * dofs + i];
            inp.max_acceleration[i] = c.v[7 * dofs + i];
            inp.max_jerk[i] = c.v[8 * dofs + i];
        }
        inp.synchronization = ruckig::Synchronization::Time;
        bool valid = false;
        try {
            valid = otg.validate_input(inp, false, true);
        } catch (const std::exception&) {
            valid = false;
        }
        if (!valid) continue;
        const auto t0 = std::chrono::steady_clock::now();
        ruckig::Result r;
        try {
            r = otg.calculate(inp, traj);
        } catch (const std::exception&) {
            r = ruckig::Result::Error;
        }
        const auto t1 = std::chrono::steady_clock::now();
        if (r < 0) ++errors;
        times.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
    std::sort(times.begin(), times.end());
    if (times.empty()) return;
    const double med = times[times.size() / 2];
    const double p99 = times[static_cast<size_t>(0.99 * times.size())];
    std::printf("  %zu DoF (%s): median %.2f us, p99 %.2f us, max %.2f us (%zu cases, %zu errors)\n", dofs, label,
                med * 1e6, p99 * 1e6, times.back() * 1e6, times.size(), errors);
}

template <size_t D>
static void run_static(const std::vector<Case>& cases) {
    ruckig::Ruckig<D> otg;
    ruckig::InputParameter<D> inp;
    ruckig::Trajectory<D> traj;
    run("compile-time DoFs", D, otg, inp, traj, cases);
}

static void run_dynamic(size_t dofs, const std::vector<Case>& cases) {
    ruckig::Ruckig<ruckig::DynamicDOFs> otg(dofs);
    ruckig::InputParameter<ruckig::DynamicDOFs> inp(dofs);
    ruckig::Trajectory<ruckig::DynamicDOFs> traj(dofs);
    run("dynamic DoFs", dofs, otg, inp, traj, cases);
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s CASES.txt\n", argv[0]);
        return 2;
    }
    std::ifstream f(argv[1]);
    std::vector<Case> cases;
    std::string line;
    while (std::getline(f, line)) {
        std::istringstream s(line);
        Case c;
        if (!(s >> c.dofs)) continue;
        c.v.resize(9 * c.dofs);
        for (auto& x : c.v) s >> x;
        if (s) cases.push_back(std::move(c));
    }
    std::printf("ruckig 0.19.4 C++ (g++ -O3 -march=native), calculate() per call, %zu cases read:\n", cases.size());
    // Two passes: the first warms the caches and the branch predictors, the second is reported.
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) std::printf("(second pass)\n");
        run_static<1>(cases);
        run_dynamic(1, cases);
        run_static<3>(cases);
        run_dynamic(3, cases);
        run_static<6>(cases);
        run_dynamic(6, cases);
        run_static<7>(cases);
        run_dynamic(7, cases);
    }
    return 0;
}
