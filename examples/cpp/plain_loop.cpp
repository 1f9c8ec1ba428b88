// A plain 1 kHz servo loop in C++17 with the header-only wrapper (shearcut.hpp):
// shearcut's controller against the simulated plant, in lockstep (as fast as the
// model runs) or paced to the wall clock with --paced.
//
//   plain_loop [SCENARIO [CONTROLLER [CSV]]] [--paced]
//
// The same arguments, rows and exit codes as examples/c/plain_loop.c.
// Guide: docs/embedding.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "shearcut.hpp"
#include "tick_csv.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> args;
  bool paced = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--paced") paced = true; else args.push_back(a);
  }
  const std::string scenario = args.size() > 0 ? args[0] : "loop-potato-whole-realtime";
  const std::string choice = args.size() > 1 ? args[1] : "mpc";
  try {
    shearcut::Setup setup(scenario, choice);
    const shearcut::Task task = setup.task();
    shearcut::Controller controller(setup);
    shearcut::Plant plant(setup);
    std::FILE* csv = args.size() > 2 ? std::fopen(args[2].c_str(), "w") : nullptr;

    // The first command is the arm at rest; then reading -> tick -> command -> step.
    shearcut::Command command{};
    shearcut::Reading reading{};
    shearcut::Truth truth{};
    shearcut::Telemetry telemetry{};
    if (plant.step(command, reading, truth) != SHEARCUT_STATUS_OK) {
      std::fprintf(stderr, "plain_loop: %s\n", shearcut::last_error());
      return 1;
    }
    const char* end = "timed_out";
    double peak_fv = 0.0, peak_fh = 0.0;
    unsigned long long tick = 0, overruns = 0;
    const auto period = std::chrono::nanoseconds(static_cast<long long>(task.period * 1e9));
    auto next = std::chrono::steady_clock::now();
    while (tick < task.max_ticks) {
      if (controller.tick(reading, command) != SHEARCUT_STATUS_OK ||
          controller.telemetry(telemetry) != SHEARCUT_STATUS_OK) {
        std::fprintf(stderr, "plain_loop: %s\n", shearcut::last_error());
        return 1;
      }
      ++tick;
      if (plant.step(command, reading, truth) != SHEARCUT_STATUS_OK) {
        std::fprintf(stderr, "plain_loop: %s\n", shearcut::last_error());
        end = "failed";
        break;
      }
      if (csv) write_tick_row(csv, tick, reading, truth, telemetry);
      peak_fv = std::max(peak_fv, truth.force[1]);
      peak_fh = std::max(peak_fh, std::fabs(truth.force[2]));
      if (truth.crack_depth >= task.target_depth) { end = "completed"; break; }
      // At rest below 1 nm/s, as the Rust runner (src/closed_loop/runner.rs).
      const double speed2 = reading.velocity[0] * reading.velocity[0] +
                            reading.velocity[1] * reading.velocity[1] +
                            reading.velocity[2] * reading.velocity[2];
      const bool at_rest = speed2 < 1e-18;
      if (telemetry.phase == SHEARCUT_PHASE_DONE && at_rest) { end = "controller_done"; break; }
      if (paced) {  // hold the servo period against the wall clock
        next += period;
        if (std::chrono::steady_clock::now() > next) ++overruns;
        else std::this_thread::sleep_until(next);
      }
    }
    if (csv) std::fclose(csv);
    std::printf("plain_loop (C++): %s, %s after %llu ticks; work %.4f J, peak Fv %.3f N, "
                "peak Fh %.3f N, depth %.2f mm", controller.name(), end, tick, truth.work,
                peak_fv, peak_fh, 1e3 * truth.crack_depth);
    if (paced) std::printf(", %llu overruns of the %.1f ms period", overruns, 1e3 * task.period);
    std::printf("\n");
    return std::string(end) == "failed" ? 1 : 0;
  } catch (const shearcut::Error& e) {
    std::fprintf(stderr, "plain_loop: %s\n", e.what());
    const bool bad_input = e.status() == SHEARCUT_STATUS_CONFIG ||
                           e.status() == SHEARCUT_STATUS_INVALID_ARGUMENT;
    return bad_input ? 2 : 1;
  }
}
