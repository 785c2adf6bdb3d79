#!/usr/bin/env python3
"""Break the guarded code on purpose, one mutation at a time, and check that a test fails.

Each mutation replaces one piece of code and runs the tests that guard it; a
mutation the tests do not catch is a hole in the suite. The files are restored
whatever happens. `make mutate` runs them all (about 15 minutes on 2 cores).
"""
from __future__ import annotations

import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


@dataclass
class Mutation:
    name: str
    path: str
    old: str
    new: str
    tests: list[str]


MUTATIONS = [
    Mutation("no repair of a line cut by a kill", "driver/table.py",
             'if not raw.endswith(b"\\n"):', "if False:",
             ["tests/test_driver.py::test_a_table_is_validated_on_load_and_bad_lines_go_aside_by_number"]),
    Mutation("no kill of running cases on Ctrl-C or a signal", "driver/sweep.py",
             "        RUNNING.kill_all()\n        raise", "        raise",
             ["tests/test_driver.py::test_killing_a_sweep_leaves_no_solver_running_and_resumes"]),
    Mutation("repairs written in place, not atomically", "driver/table.py",
             "        os.replace(tmp, path)", "        path.write_bytes(b''); path.write_bytes(tmp.read_bytes())",
             ["tests/test_driver.py::test_a_kill_during_a_table_repair_loses_nothing"]),
    Mutation("bad rows kept", "driver/table.py",
             "        if reason:\n            result.bad.append((number, reason, text))\n            continue",
             "        pass",
             ["tests/test_driver.py::test_a_table_is_validated_on_load_and_bad_lines_go_aside_by_number"]),
    Mutation("exit code ignored when a summary exists", "driver/run.py",
             "    if EXIT_OF_STATUS[status] != exit_code:", "    if False:",
             ["tests/test_driver.py::test_every_solver_fault_is_a_failed_row_with_its_reason"]),
    Mutation("no reaping of a leftover solver on resume", "driver/run.py",
             "    reap_leftover(workdir)\n", "",
             ["tests/test_driver.py::test_a_resumed_sweep_kills_a_leftover_solver_of_its_case"]),
    Mutation("comments change the fingerprint", "driver/freefem.py",
             '    return "".join(_COMMENTS.sub("", path.read_text()).split())', "    return path.read_text()",
             ["tests/test_repo.py::test_the_fingerprint_ignores_comments_and_whitespace"]),
    Mutation("output written without the line check", "edp/lib/output.idp",
             'check = check + " && test \\"$(wc -l < " + partName[k] + ".part)\\" -eq " + partLines[k];',
             'check = check + "";',
             ["tests/test_reliability.py::test_a_failed_write_exits_4_and_keeps_the_earlier_files"]),
    Mutation("penalties beyond rounding accepted", "edp/lib/levels.idp",
             "if (method != \"lagrange\" && kappa > maxPenaltyND)", "if (false)",
             ["tests/test_reliability.py::test_penalties_rounding_would_fake_are_refused_up_front",
              "tests/test_options.py::test_bad_input_is_one_line_on_stderr_naming_the_option"]),
    Mutation("a far-off answer reported as converged", "edp/lib/status.idp",
             'if (status == "converged" && offByMore) status = "inaccurate";', "",
             ["tests/test_scale_free.py::test_a_far_off_result_is_inaccurate_not_converged"]),
    Mutation("an explicit -tol met at the rounding floor", "edp/lib/newton.idp",
             "      if (!tolGiven && residual < acceptFloor)", "      if (residual < acceptFloor)",
             ["tests/test_reliability.py::test_an_explicit_tolerance_below_the_rounding_floor_is_roundoff_not_converged"]),
    Mutation("the scene's stress unit dropped", "edp/lib/scene.idp",
             "real stressScale = Estar*depth/lengthScale;", "real stressScale = depth/lengthScale;",
             ["tests/test_scale_free.py::test_one_scene_in_three_unit_systems_gives_the_same_run"]),
    Mutation("lagrange releases nodes by the gap only", "edp/lib/lagrange.idp",
             "nodalForce[j] + c*surfaceMass[j]*surfaceGap[j] > 0", "surfaceGap[j] > 0",
             ["tests/test_physics.py::test_lagrange_closes_every_node_to_rounding_for_any_augmentation"]),
    Mutation("no domain term in the estimate", "edp/lib/estimate.idp",
             "estimateDomain[k] = model != \"plane\" ? domainCoefficient[k]/Lratio : 0;",
             "estimateDomain[k] = 0;",
             ["tests/test_reliability.py::test_a_converged_run_far_from_its_estimate_is_inaccurate"]),
    Mutation("missing value absorbed by the next option", "edp/lib/options.idp",
             "      if (!missing) missing = optionIndex(ARGV[i]) >= 0;", "",
             ["tests/test_options.py::test_bad_input_is_one_line_on_stderr_naming_the_option"]),
    Mutation("Uzawa without its stall stop", "edp/lib/newton.idp",
             '    if (s - bestUpdate >= 50) { status = "stalled"; return 0; }', "",
             ["tests/test_reliability.py::test_uzawa_at_a_hopeless_penalty_stops_early"]),
    Mutation("elliptical Hertz with its axes swapped", "edp/lib/hertz.idp",
             "hertzEllipseX = Rx >= Ry ? aLong : bShort;", "hertzEllipseX = Rx >= Ry ? bShort : aLong;",
             ["tests/test_3d.py::test_an_ellipsoid_is_solved_in_3d_within_2_percent_of_elliptical_hertz"]),
    Mutation("-model auto solves a sphere in 3D", "edp/lib/scene.idp",
             'else if (Rx == Ry) { model = "axi";', 'else if (Rx == Ry) { model = "3d";',
             ["tests/test_3d.py::test_model_auto_never_models_more_than_the_scene_needs"]),
    Mutation("the 3D outline stops at the first open sample", "edp/lib/measure.idp",
             "    if (rayGap(t, s) > -edgeGap) { lo = s; hi = s + reach/samples; }",
             "    if (rayGap(t, s) > -edgeGap && lo < 0) { lo = s; hi = s + reach/samples; }",
             ["tests/test_3d.py::test_the_outline_and_both_profiles_follow_the_hertz_ellipse"]),
]


def run(mutation: Mutation) -> bool:
    """True if a test failed (the mutation is caught)."""
    path = ROOT / mutation.path
    original = path.read_text()
    if original.count(mutation.old) != 1:
        raise SystemExit(f"{mutation.name}: the code to mutate is not found once in {mutation.path}")
    try:
        path.write_text(original.replace(mutation.old, mutation.new))
        proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider",
                               *mutation.tests], cwd=ROOT, capture_output=True, text=True)
        return proc.returncode != 0
    finally:
        path.write_text(original)


def main() -> int:
    caught = 0
    for mutation in MUTATIONS:
        ok = run(mutation)
        caught += ok
        print(f"{'caught' if ok else 'MISSED'}  {mutation.name}  ({mutation.path})", flush=True)
    print(f"{caught} of {len(MUTATIONS)} mutations caught")
    return 0 if caught == len(MUTATIONS) else 1


if __name__ == "__main__":
    sys.exit(main())
