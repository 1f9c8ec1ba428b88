// shearcut's controller in a class shaped like a ros2_control controller
// (controller_interface::ControllerInterface: on_configure, on_activate,
// update(time, period), on_deactivate), driven by a loop shaped like the
// controller manager's (read -> update -> write) against the simulated plant as
// its hardware. No ROS is needed or used: the state and command interfaces
// are plain doubles here, as ros2_control's loaned interfaces are.
//
//   ros2_control_style [SCENARIO [CONTROLLER [CSV]]]
//
// Same rows and exit codes as plain_loop; the run is bit-identical to it.
// docs/embedding.md says how to move the class into a real plugin.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "shearcut.hpp"
#include "tick_csv.hpp"

namespace {

enum class CallbackReturn { SUCCESS, FAILURE, ERROR };
enum class ReturnType { OK, ERROR };

/// The state interfaces the controller claims: in a real plugin,
/// "knife/position.{x,y,z}" and "knife/velocity.{x,y,z}" from the arm's
/// Cartesian state (the knife frame: heel end of the edge, world frame y up),
/// "ft_sensor/{force,torque}.{x,y,z}" from the wrist F/T broadcaster, and the
/// arm's status.
struct StateInterfaces {
  double position[3];
  double velocity[3];
  double wrench[6];
  std::uint32_t status;
  double violation;
};

/// The command interfaces it claims: "knife/velocity.{x,y,z}", a Cartesian
/// twist of the knife frame in the world frame, m/s.
struct CommandInterfaces {
  double velocity[3];
};

/// shearcut's knife controller as a ros2_control-shaped controller.
class KnifeSlicingController {
 public:
  /// Parameters would come from the node ("scenario", "controller"). Builds
  /// everything (allocates, may take a second for the MPC): never in update().
  CallbackReturn on_configure(const std::string& scenario, const std::string& choice) {
    try {
      setup_.emplace(scenario, choice);
      controller_.emplace(*setup_);
      return CallbackReturn::SUCCESS;
    } catch (const shearcut::Error& e) {
      std::fprintf(stderr, "on_configure: %s\n", e.what());
      return CallbackReturn::ERROR;
    }
  }
  /// Claims the interfaces (in a real plugin: state_interfaces_, command_interfaces_).
  void assign_interfaces(const StateInterfaces* state, CommandInterfaces* command) {
    state_ = state;
    command_ = command;
  }
  /// Starts from a fresh controller (a second activation cuts anew).
  CallbackReturn on_activate() {
    if (!controller_ || !state_ || !command_) return CallbackReturn::ERROR;
    if (activations_++ > 0) controller_->reset();
    return CallbackReturn::SUCCESS;
  }
  /// One servo tick: state interfaces -> reading -> tick -> command interfaces.
  /// Real-time safe: no allocation, no exception, no lock.
  ReturnType update(double time, double /*period*/) noexcept {
    shearcut::Reading reading{};
    reading.time = time;
    for (int i = 0; i < 3; ++i) reading.position[i] = state_->position[i];
    for (int i = 0; i < 3; ++i) reading.velocity[i] = state_->velocity[i];
    for (int i = 0; i < 6; ++i) reading.wrench[i] = state_->wrench[i];
    reading.status = state_->status;
    reading.violation = state_->violation;
    shearcut::Command command{};
    if (controller_->tick(reading, command) != SHEARCUT_STATUS_OK ||
        controller_->telemetry(telemetry_) != SHEARCUT_STATUS_OK) {
      for (double& v : command_->velocity) v = 0.0;  // hold still; the arm brakes on its own
      return ReturnType::ERROR;
    }
    for (int i = 0; i < 3; ++i) command_->velocity[i] = command.velocity[i];
    return ReturnType::OK;
  }
  /// Leaves a zero twist on the command interfaces.
  CallbackReturn on_deactivate() {
    for (double& v : command_->velocity) v = 0.0;
    return CallbackReturn::SUCCESS;
  }
  const shearcut::Telemetry& telemetry() const { return telemetry_; }
  const char* name() const { return controller_->name(); }
  const shearcut::Task task() const { return setup_->task(); }

 private:
  std::optional<shearcut::Setup> setup_;
  std::optional<shearcut::Controller> controller_;
  const StateInterfaces* state_ = nullptr;
  CommandInterfaces* command_ = nullptr;
  shearcut::Telemetry telemetry_{};
  int activations_ = 0;
};

/// The simulated plant as ros2_control hardware: read() fills the state
/// interfaces, write() executes the command interfaces for one period.
class SimulatedKnifeHardware {
 public:
  explicit SimulatedKnifeHardware(const shearcut::Setup& setup) : plant_(setup) {}
  /// Executes the command interfaces for one servo period.
  bool write(const CommandInterfaces& command) {
    shearcut::Command c{};
    for (int i = 0; i < 3; ++i) c.velocity[i] = command.velocity[i];
    return plant_.step(c, reading_, truth_) == SHEARCUT_STATUS_OK;
  }
  /// Copies the last reading into the state interfaces; returns its time.
  double read(StateInterfaces& state) const {
    for (int i = 0; i < 3; ++i) state.position[i] = reading_.position[i];
    for (int i = 0; i < 3; ++i) state.velocity[i] = reading_.velocity[i];
    for (int i = 0; i < 6; ++i) state.wrench[i] = reading_.wrench[i];
    state.status = reading_.status;
    state.violation = reading_.violation;
    return reading_.time;
  }
  const shearcut::Reading& reading() const { return reading_; }
  const shearcut::Truth& truth() const { return truth_; }

 private:
  shearcut::Plant plant_;
  shearcut::Reading reading_{};
  shearcut::Truth truth_{};
};

}  // namespace

int main(int argc, char** argv) {
  const std::string scenario = argc > 1 ? argv[1] : "loop-potato-whole-realtime";
  const std::string choice = argc > 2 ? argv[2] : "mpc";
  std::FILE* csv = argc > 3 ? std::fopen(argv[3], "w") : nullptr;

  KnifeSlicingController controller;
  if (controller.on_configure(scenario, choice) != CallbackReturn::SUCCESS) return 2;
  const shearcut::Task task = controller.task();
  std::unique_ptr<SimulatedKnifeHardware> hardware;
  try {
    shearcut::Setup setup(scenario, choice);
    hardware = std::make_unique<SimulatedKnifeHardware>(setup);
  } catch (const shearcut::Error& e) {
    std::fprintf(stderr, "hardware: %s\n", e.what());
    return 1;
  }
  StateInterfaces state{};
  CommandInterfaces command{};  // zero twist: the arm at rest
  controller.assign_interfaces(&state, &command);
  if (controller.on_activate() != CallbackReturn::SUCCESS) return 1;

  // The controller manager's loop: write the last command, read the state, update.
  const char* end = "timed_out";
  unsigned long long tick = 0;
  if (!hardware->write(command)) return 1;
  double time = hardware->read(state);
  while (tick < task.max_ticks) {
    if (controller.update(time, task.period) != ReturnType::OK) {
      std::fprintf(stderr, "update: %s\n", shearcut::last_error());
      return 1;
    }
    ++tick;
    if (!hardware->write(command)) {
      std::fprintf(stderr, "write: %s\n", shearcut::last_error());
      end = "failed";
      break;
    }
    time = hardware->read(state);
    const shearcut::Truth& truth = hardware->truth();
    if (csv) write_tick_row(csv, tick, hardware->reading(), truth, controller.telemetry());
    if (truth.crack_depth >= task.target_depth) { end = "completed"; break; }
    // At rest below 1 nm/s, as the Rust runner (src/closed_loop/runner.rs).
    const double speed2 = state.velocity[0] * state.velocity[0] +
                          state.velocity[1] * state.velocity[1] +
                          state.velocity[2] * state.velocity[2];
    const bool at_rest = speed2 < 1e-18;
    if (controller.telemetry().phase == SHEARCUT_PHASE_DONE && at_rest) {
      end = "controller_done";
      break;
    }
  }
  controller.on_deactivate();
  if (csv) std::fclose(csv);
  std::printf("ros2_control_style: %s, %s after %llu ticks; work %.4f J, depth %.2f mm\n",
              controller.name(), end, tick, hardware->truth().work,
              1e3 * hardware->truth().crack_depth);
  return std::string(end) == "failed" ? 1 : 0;
}
