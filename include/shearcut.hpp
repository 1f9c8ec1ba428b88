// shearcut.hpp: a header-only C++17 wrapper of the shearcut C ABI (shearcut.h).
//
// RAII handles (Setup, Controller, Plant) that free themselves; construction
// throws shearcut::Error (it loads files and builds models: never on a servo
// tick); the tick path (Controller::tick, Plant::step, Controller::telemetry)
// is noexcept and returns a Status. Link against libshearcut_ffi (.a or .so).
// Guide: docs/embedding.md. Units: SI (m, s, N, N m, J); world frame y up,
// the knife moving in its plane (y, z).
#ifndef SHEARCUT_HPP
#define SHEARCUT_HPP

#include <memory>
#include <stdexcept>
#include <string>

#include "shearcut.h"

namespace shearcut {

using Reading = ShearcutReading;
using Command = ShearcutCommand;
using Truth = ShearcutTruth;
using Telemetry = ShearcutTelemetry;
using Task = ShearcutTask;
using Status = ShearcutStatus;

/// A failed construction or reset: the status and shearcut's one-line reason.
class Error : public std::runtime_error {
 public:
  Error(Status status, const std::string& what) : std::runtime_error(what), status_(status) {}
  /// The status the C call returned.
  Status status() const noexcept { return status_; }

 private:
  Status status_;
};

/// The calling thread's last error message (valid until its next failing call).
inline const char* last_error() noexcept { return shearcut_last_error(); }

/// The library's version, "MAJOR.MINOR.PATCH".
inline const char* version() noexcept { return shearcut_version(); }

namespace detail {
inline void check(Status status) {
  if (status != SHEARCUT_STATUS_OK) {
    throw Error(status, shearcut_last_error());
  }
}
struct SetupFree {
  void operator()(ShearcutSetup* p) const noexcept { shearcut_setup_free(p); }
};
struct ControllerFree {
  void operator()(ShearcutController* p) const noexcept { shearcut_controller_free(p); }
};
struct PlantFree {
  void operator()(ShearcutPlant* p) const noexcept { shearcut_plant_free(p); }
};
}  // namespace detail

/// A scenario (TOML path or built-in name) set up for a controller
/// ("mpc", "press", "slice:XI", "force:N"; empty: the scenario's own).
class Setup {
 public:
  explicit Setup(const std::string& scenario, const std::string& controller = "") {
    ShearcutSetup* raw = nullptr;
    detail::check(shearcut_setup_new(scenario.c_str(),
                                     controller.empty() ? nullptr : controller.c_str(), &raw));
    handle_.reset(raw);
  }
  /// The cut the controller is told, and the simulated loop's limits.
  Task task() const {
    Task t{};
    detail::check(shearcut_setup_task(handle_.get(), &t));
    return t;
  }
  /// The C handle (owned by this object).
  const ShearcutSetup* get() const noexcept { return handle_.get(); }

 private:
  std::unique_ptr<ShearcutSetup, detail::SetupFree> handle_;
};

/// The knife controller. Movable, not copyable; one thread at a time.
class Controller {
 public:
  explicit Controller(const Setup& setup) {
    ShearcutController* raw = nullptr;
    detail::check(shearcut_controller_new(setup.get(), &raw));
    handle_.reset(raw);
  }
  /// One servo tick: reading in, command out. Allocates nothing; never throws.
  Status tick(const Reading& reading, Command& command) noexcept {
    return shearcut_controller_tick(handle_.get(), &reading, &command);
  }
  /// What the last tick planned. Never throws.
  Status telemetry(Telemetry& out) const noexcept {
    return shearcut_controller_telemetry(handle_.get(), &out);
  }
  /// The controller's short name ("mpc", "slice:0.75", ...).
  const char* name() const noexcept { return shearcut_controller_name(handle_.get()); }
  /// A fresh controller from the same setup (allocates: not on the tick).
  void reset() { detail::check(shearcut_controller_reset(handle_.get())); }
  /// The C handle (owned by this object).
  ShearcutController* get() noexcept { return handle_.get(); }

 private:
  std::unique_ptr<ShearcutController, detail::ControllerFree> handle_;
};

/// The simulated plant: arm, F/T sensor and object. One thread at a time.
class Plant {
 public:
  explicit Plant(const Setup& setup) {
    ShearcutPlant* raw = nullptr;
    detail::check(shearcut_plant_new(setup.get(), &raw));
    handle_.reset(raw);
  }
  /// Executes `command` for one servo period; the arm's reading and the
  /// simulated truth out. Allocates nothing on this thread; never throws.
  Status step(const Command& command, Reading& reading, Truth& truth) noexcept {
    return shearcut_plant_step(handle_.get(), &command, &reading, &truth);
  }
  /// As above, without the truth (what a real arm's bridge would give).
  Status step(const Command& command, Reading& reading) noexcept {
    return shearcut_plant_step(handle_.get(), &command, &reading, nullptr);
  }
  /// The knife back at its start, the object intact (allocates).
  void reset() { detail::check(shearcut_plant_reset(handle_.get())); }
  /// The C handle (owned by this object).
  ShearcutPlant* get() noexcept { return handle_.get(); }

 private:
  std::unique_ptr<ShearcutPlant, detail::PlantFree> handle_;
};

}  // namespace shearcut

#endif  // SHEARCUT_HPP
