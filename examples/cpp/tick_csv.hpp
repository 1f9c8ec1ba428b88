// One CSV row per servo tick for the C++ example loops: the reading, the
// simulated truth and the plan, every number with 17 significant digits so
// that it reads back bit for bit (ffi/tests/foreign_loops.rs does).
// Columns: tick, time, position[3], velocity[3], wrench[6], status,
// violation, force[3], torque[3], crack_depth, contact_length,
// fractured_sections, work, deformation, slice_push_ratio, phase.
#ifndef SHEARCUT_EXAMPLES_TICK_CSV_HPP
#define SHEARCUT_EXAMPLES_TICK_CSV_HPP

#include <cstdio>

#include "shearcut.hpp"

inline void write_tick_row(std::FILE* csv, unsigned long long tick, const shearcut::Reading& r,
                           const shearcut::Truth& t, const shearcut::Telemetry& m) {
  std::fprintf(csv, "%llu,%.17g", tick, r.time);
  for (double v : r.position) std::fprintf(csv, ",%.17g", v);
  for (double v : r.velocity) std::fprintf(csv, ",%.17g", v);
  for (double v : r.wrench) std::fprintf(csv, ",%.17g", v);
  std::fprintf(csv, ",%u,%.17g", r.status, r.violation);
  for (double v : t.force) std::fprintf(csv, ",%.17g", v);
  for (double v : t.torque) std::fprintf(csv, ",%.17g", v);
  std::fprintf(csv, ",%.17g,%.17g,%llu,%.17g,%.17g,%.17g,%u\n", t.crack_depth, t.contact_length,
               static_cast<unsigned long long>(t.fractured_sections), t.work, t.deformation,
               m.slice_push_ratio, m.phase);
}

#endif  // SHEARCUT_EXAMPLES_TICK_CSV_HPP
