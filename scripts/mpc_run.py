"""One `shearcut run SCENARIO --controller mpc --transport inproc` of a
scenario given as TOML text, for the scripts that tabulate such runs."""

import json
import subprocess
import sys


def run_mpc(binary, text, out):
    """Writes `text` to OUT/scenario.toml, runs the MPC on it in process
    into OUT/run and returns that directory and the parsed summary.json;
    exits with shearcut's own message if the run fails."""
    path = out / "scenario.toml"
    path.write_text(text)
    done = subprocess.run(
        [binary, "run", str(path), "--controller", "mpc", "--transport", "inproc",
         "--out", str(out / "run")],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"{path}: shearcut exited with {done.returncode}: {done.stderr.strip()}")
    return out / "run", json.loads((out / "run" / "summary.json").read_text())
