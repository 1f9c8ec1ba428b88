/* A plain servo loop in C99 against shearcut's C ABI: the controller and the
 * simulated plant, one command per 1 ms period, in lockstep (as fast as the
 * model runs) or paced to the wall clock with --paced.
 *
 *   plain_loop [SCENARIO [CONTROLLER [CSV]]] [--paced]
 *
 * SCENARIO: a TOML path or built-in name (default loop-potato-whole-realtime,
 * the main job's); CONTROLLER: mpc, press, slice:XI, force:N (default mpc);
 * CSV: a file for one row per tick (the reading, the truth, the plan), every
 * number with 17 significant digits so it reads back bit for bit.
 * Exit code 0 on a completed cut, 1 if the loop failed, 2 on bad input.
 * Guide: docs/embedding.md. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "shearcut.h"

static int fail(const char *what, ShearcutStatus status) {
    fprintf(stderr, "plain_loop: %s: %s\n", what, shearcut_last_error());
    return status == SHEARCUT_STATUS_CONFIG || status == SHEARCUT_STATUS_INVALID_ARGUMENT ? 2 : 1;
}

static void write_row(FILE *csv, unsigned long long tick, const ShearcutReading *r,
                      const ShearcutTruth *t, const ShearcutTelemetry *m) {
    fprintf(csv, "%llu,%.17g", tick, r->time);
    for (int i = 0; i < 3; ++i) fprintf(csv, ",%.17g", r->position[i]);
    for (int i = 0; i < 3; ++i) fprintf(csv, ",%.17g", r->velocity[i]);
    for (int i = 0; i < 6; ++i) fprintf(csv, ",%.17g", r->wrench[i]);
    fprintf(csv, ",%u,%.17g", r->status, r->violation);
    for (int i = 0; i < 3; ++i) fprintf(csv, ",%.17g", t->force[i]);
    for (int i = 0; i < 3; ++i) fprintf(csv, ",%.17g", t->torque[i]);
    fprintf(csv, ",%.17g,%.17g,%llu,%.17g,%.17g,%.17g,%u\n", t->crack_depth, t->contact_length,
            (unsigned long long)t->fractured_sections, t->work, t->deformation,
            m->slice_push_ratio, m->phase);
}

int main(int argc, char **argv) {
    const char *args[3] = {"loop-potato-whole-realtime", "mpc", NULL};
    int paced = 0, n = 0;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--paced") == 0) paced = 1;
        else if (n < 3) args[n++] = argv[i];
    }
    ShearcutSetup *setup = NULL;
    ShearcutController *controller = NULL;
    ShearcutPlant *plant = NULL;
    ShearcutStatus s = shearcut_setup_new(args[0], args[1], &setup);
    if (s != SHEARCUT_STATUS_OK) return fail("setup", s);
    ShearcutTask task;
    shearcut_setup_task(setup, &task);
    if ((s = shearcut_controller_new(setup, &controller)) != SHEARCUT_STATUS_OK) return fail("controller", s);
    if ((s = shearcut_plant_new(setup, &plant)) != SHEARCUT_STATUS_OK) return fail("plant", s);
    shearcut_setup_free(setup); /* the controller and the plant keep their own copies */
    FILE *csv = args[2] ? fopen(args[2], "w") : NULL;
    if (args[2] && !csv) { fprintf(stderr, "plain_loop: cannot write %s\n", args[2]); return 2; }

    /* The first command is the arm at rest; then reading -> tick -> command -> step. */
    ShearcutCommand command = {{0.0, 0.0, 0.0}};
    ShearcutReading reading;
    ShearcutTruth truth;
    ShearcutTelemetry telemetry;
    if ((s = shearcut_plant_step(plant, &command, &reading, &truth)) != SHEARCUT_STATUS_OK) return fail("step", s);
    const char *end = "timed_out";
    double peak_fv = 0.0, peak_fh = 0.0;
    unsigned long long tick = 0, overruns = 0;
    struct timespec next;
    clock_gettime(CLOCK_MONOTONIC, &next);
    while (tick < task.max_ticks) {
        if ((s = shearcut_controller_tick(controller, &reading, &command)) != SHEARCUT_STATUS_OK) return fail("tick", s);
        shearcut_controller_telemetry(controller, &telemetry);
        ++tick;
        if ((s = shearcut_plant_step(plant, &command, &reading, &truth)) != SHEARCUT_STATUS_OK) {
            end = "failed";
            fail("step", s);
            break;
        }
        if (csv) write_row(csv, tick, &reading, &truth, &telemetry);
        peak_fv = fmax(peak_fv, truth.force[1]);
        peak_fh = fmax(peak_fh, fabs(truth.force[2]));
        if (truth.crack_depth >= task.target_depth) { end = "completed"; break; }
        /* At rest below 1 nm/s, as the Rust runner (src/closed_loop/runner.rs). */
        double speed2 = reading.velocity[0] * reading.velocity[0] +
                        reading.velocity[1] * reading.velocity[1] +
                        reading.velocity[2] * reading.velocity[2];
        if (telemetry.phase == SHEARCUT_PHASE_DONE && speed2 < 1e-18) { end = "controller_done"; break; }
        if (paced) { /* hold the 1 kHz (task.period) cadence against the wall clock */
            long step_ns = (long)(task.period * 1e9);
            next.tv_nsec += step_ns;
            while (next.tv_nsec >= 1000000000L) { next.tv_nsec -= 1000000000L; ++next.tv_sec; }
            struct timespec now;
            clock_gettime(CLOCK_MONOTONIC, &now);
            if (now.tv_sec > next.tv_sec || (now.tv_sec == next.tv_sec && now.tv_nsec > next.tv_nsec)) ++overruns;
            else clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
        }
    }
    if (csv) fclose(csv);
    printf("plain_loop (C): %s, %s after %llu ticks; work %.4f J, peak Fv %.3f N, peak Fh %.3f N, depth %.2f mm",
           shearcut_controller_name(controller), end, tick, truth.work, peak_fv, peak_fh, 1e3 * truth.crack_depth);
    if (paced) printf(", %llu overruns of the %.1f ms period", overruns, 1e3 * task.period);
    printf("\n");
    shearcut_controller_free(controller);
    shearcut_plant_free(plant);
    return strcmp(end, "failed") == 0 ? 1 : 0;
}
