"""The seed scene (edp/hertz.edp's defaults) and Hertz's answer for it, for the peers of
make bench (each a script run by its own Python: this module sits beside them)."""
import json
import math
import time

E, NU, R, D = 10.0, 0.3, 0.5, 0.02
A_H = math.sqrt(R * D)
E_STAR = E / (1 - NU**2)
F_H = 4.0 / 3.0 * E_STAR * A_H * D
P0_H = 3 * F_H / (2 * math.pi * A_H**2)


def finish(out, started):
    """Print a peer's result as one JSON line, with the whole process's wall time
    since `started` (imports included); the exit code says whether it converged."""
    out["wall_time_total"] = time.perf_counter() - started
    print(json.dumps(out))
    return 0 if out["converged"] else 1
