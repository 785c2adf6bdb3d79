"""No false convergence, no silent write failure, limits with clear messages (hertz.edp)."""
import math
import os
import re
import subprocess
import time

import pytest

from driver import freefem

from conftest import RUN_FILES_2D


def run_limited(args: list[str], file_kb: int) -> subprocess.CompletedProcess:
    """hertz.edp with files capped at file_kb: writes past it fail (EFBIG), as on a full disk."""
    cmd = " ".join(f"'{a}'" for a in freefem.command(args))
    return subprocess.run(["bash", "-c", f"ulimit -f {file_kb}; trap '' XFSZ; exec {cmd}"],
                          capture_output=True, text=True, env=freefem.freefem_env(), timeout=300)


def test_a_failed_write_exits_4_and_keeps_the_earlier_files(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "summary.csv").write_text("an earlier result\n")
    proc = run_limited(["-n", "8", "-out", str(out)], file_kb=4)  # profile.csv needs more
    assert proc.returncode == 4, proc.stdout
    assert "cannot write the output files" in proc.stderr  # errors go to stderr, apart from the results
    assert (out / "summary.csv").read_text() == "an earlier result\n"  # not replaced by a short file
    assert not list(out.glob("*.part"))


def test_a_failed_vtk_write_exits_4(tmp_path):
    proc = run_limited(["-n", "8", "-vtk", str(tmp_path / "f.vtu")], file_kb=64)
    assert proc.returncode == 4 and "cannot write the VTK files" in proc.stderr


def test_an_explicit_tolerance_below_the_rounding_floor_is_roundoff_not_converged(solve):
    run = solve("-gamma", "1e6", "-tol", "1e-14")
    assert run.exit_code == 3 and run.summary["status"] == "roundoff", run.output
    assert "rounding floor" in run.output
    # without -tol the same penalty converges at its floor (1e-7 here, below 1e-5)
    default = solve("-gamma", "1e6").summary
    assert default["status"] == "converged" and default["residual"] < 1e-5


@pytest.mark.parametrize("args", [["-E", "1e-6", "-kpen", "1e10"], ["-E", "1e-6", "-kpen", "1e15"],
                                  ["-R", "1e6", "-d", "1e4", "-kpen", "1e12"], ["-kpen", "4e-320"]])
def test_penalties_rounding_would_fake_are_refused_up_front(solve, args):
    run = solve(*args)
    assert run.exit_code == 2 and "-kpen" in run.stderr and "E*/h" in run.stderr + run.stdout


def test_uzawa_at_a_hopeless_penalty_stops_early(solve):
    run = solve("-method", "uzawa", "-gamma", "1e-6", "-maxit", "100000", timeout=120)
    assert run.exit_code == 3 and run.summary["status"] == "stalled"


def test_uzawa_on_a_punch_converges_from_the_least_penalty_it_takes(solve):
    run = solve("-shape", "punch", "-method", "uzawa", "-n", "32", "-gamma", "50", timeout=120)
    assert run.exit_code == 0 and run.summary["status"] == "converged", run.output
    assert "face-lifts" not in str(run.summary["warnings"])


def test_a_mesh_beyond_maxdof_is_refused_before_meshing(solve):
    start = time.perf_counter()
    run = solve("-n", "300", "-L", "1000")  # about 2 million dofs: minutes and gigabytes
    assert run.exit_code == 2 and "-maxdof" in run.stderr and time.perf_counter() - start < 5
    assert solve("-n", "32", "-maxdof", "1e4", "-check", "1").exit_code == 2


def run_memory_limited(args: list[str], limit_mb: int, out) -> subprocess.CompletedProcess:
    """hertz.edp under an address-space limit (ulimit -v), as a shared machine or a container sets one."""
    cmd = " ".join(f"'{a}'" for a in freefem.command(args + ["-out", str(out)]))
    return subprocess.run(["bash", "-c", f"ulimit -v {limit_mb * 1024}; exec {cmd}"],
                          capture_output=True, text=True, env=freefem.freefem_env(), timeout=300)


def test_a_mesh_beyond_the_memory_is_its_own_status_before_meshing(tmp_path):
    # n = 200 peaks at 992 MB (measured): under 900 MB it died of a segfault
    start = time.perf_counter()
    run = run_memory_limited(["-n", "200"], 900, tmp_path / "big")
    assert run.returncode == freefem.exit_code("out-of-memory") == 6, run.stdout[-500:] + run.stderr
    line = run.stderr.strip()
    assert line.count("\n") == 0 and "out of memory" in line and "ulimit -v" in line and "-n 200" in line
    assert time.perf_counter() - start < 5 and not any((tmp_path / "big").iterdir())  # nothing written
    # a mesh that fits runs under the same limit (n = 100 peaks at 249 MB)
    fits = run_memory_limited(["-n", "100"], 900, tmp_path / "fits")
    assert fits.returncode == 0 and "out of memory" not in fits.stderr


def test_accuracy_stops_at_the_memory_and_says_so(tmp_path):
    # P1 misses 1e-4 at n = 64; n = 128 needs about 440 MB by the model
    run = run_memory_limited(["-accuracy", "1e-4", "-order", "1"], 450, tmp_path)
    assert run.returncode == 5, run.stdout[-500:] + run.stderr
    assert "stopped by the memory" in run.stderr and "ulimit -v" in run.stderr


def test_a_soft_penalty_is_advised_only_a_penalty_the_scene_takes(solve):
    # a film on a rigid base at nu = 1/2 was told "use -gamma 1e+08 or more", which it refuses
    args = ("-t", "0.001", "-E2", "inf", "-nu", "0.5")
    run = solve(*args, "-gamma", "1e6")
    assert run.exit_code == 5 and "soft-penalty" in run.summary["warnings"]
    top = float(re.search(r"use -method lagrange: this scene takes -gamma up to (\S+)\)", run.stderr).group(1))
    assert solve(*args, "-gamma", repr(0.99 * top), "-check", "1").exit_code == 0
    assert solve(*args, "-gamma", repr(1.01 * top), "-check", "1").exit_code == 2


@pytest.mark.parametrize("args, cure", [
    (("-w", "0.05", "-sigma0", "5", "-order", "1"), "refine -n"),   # -accuracy is refused with -w
    (("-method", "fixedpoint", "-gamma", "0.1", "-n", "3"), "use -method lagrange or newton"),
])
def test_a_warning_advises_only_what_the_scene_takes(solve, args, cure):
    # both advised -accuracy, which they refuse; the fixed point was told to stiffen into divergence
    run = solve(*args)
    warnings = [line for line in run.stderr.splitlines() if "warning" in line]
    assert run.exit_code == 5 and any(cure in line for line in warnings), run.stderr
    assert not any("-accuracy" in line or "-gamma 100" in line for line in warnings), run.stderr


def test_a_refused_output_path_leaves_no_folder_behind(tmp_path):
    # a name too long for the file system left the folders on its way
    for option, name in (("-out", "z" * 300), ("-vtk", "z" * 300 + ".vtu")):
        proc = run_limited([option, str(tmp_path / "q1" / "q2" / name)], file_kb=10**6)
        assert proc.returncode == 2 and option in proc.stderr, proc.stderr
        assert not (tmp_path / "q1").exists()


def test_a_rerun_of_another_branch_leaves_no_file_of_the_earlier(tmp_path):
    # 3D's outline.csv and profile_y.csv stayed beside a 2D rerun's summary
    out = tmp_path / "out"
    assert run_limited(["-model", "3d", "-n", "3", "-out", str(out)], file_kb=10**6).returncode in (0, 5)
    assert (out / "outline.csv").is_file()
    assert run_limited(["-n", "8", "-out", str(out)], file_kb=10**6).returncode == 0
    assert sorted(p.name for p in out.iterdir()) == ["axis.csv", "history.csv", "path.csv", "profile.csv",
                                                      "summary.csv"]


def test_a_converged_run_far_from_its_estimate_is_inaccurate(solve):
    run = solve("-n", "4", "-L", "20", "-farfield", "clamped")  # the clamped boundary alone costs 5%
    assert run.exit_code == 5
    s = run.summary
    assert s["status"] == "inaccurate" and "estimate" in s["warnings"]
    assert s["est_err_F"] > 0.01


def test_accuracy_reaches_its_target_or_says_why(solve):
    ok = solve("-accuracy", "0.005")
    s = ok.summary
    assert ok.exit_code == 0 and s["accuracy_predicted"] <= 0.005
    assert max(abs(s["err_p0"]), abs(s["err_F"]), abs(s["err_a"])) <= 0.005
    # P1 reads 1.7% at n = 32; n = 64 needs 35k dofs
    short = solve("-accuracy", "0.001", "-order", "1", "-maxdof", "2e4")
    assert short.exit_code == 5 and "mesh limit" in short.output
    assert short.summary["status"] == "inaccurate" and "accuracy-missed" in short.summary["warnings"]


def test_a_fixed_point_at_its_rounding_floor_is_roundoff_not_diverged(solve):
    # a stable fixed point whose residual stops at 4e-13, above an explicit -tol 1e-14
    run = solve("-method", "fixedpoint", "-kpen", "10", "-tol", "1e-14")
    s = run.summary
    assert run.exit_code == 3 and s["status"] == "roundoff" and s["residual"] < 1e-10, run.output
    # beyond its stability limit it still diverges
    assert solve("-method", "fixedpoint", "-kpen", "1e4").summary["status"] == "diverged"


def test_a_diverged_run_predicts_no_accuracy_rather_than_zero_error(solve):
    # it has nothing to estimate: accuracy_predicted was 0, which reads as an exact answer
    s = solve("-method", "fixedpoint", "-kpen", "1e4").summary
    assert s["status"] == "diverged" and math.isnan(s["accuracy_predicted"]) and math.isnan(s["est_err_p0"])


# Scenes whose contact collapsed to the axis: P1 locks at nu = 0.4999 (p1-locking), and the
# medium level read the edge at 1e-9 of the contact scale. FreeFEM stops a run on a division by
# zero or on mesh points closer than 1e-7 of its diameter (exit 8: no status, *.part files left).
# (The punch's contact radius is now its outermost node in contact, the face's edge: its locked
# face is named as lifted, face-lifts, and no longer divides its axis output by a zero radius.)
COLLAPSED = {
    "a punch, its axis output": ("-nu", "0.4999", "-order", "1", "-shape", "punch"),
    "a cone under its load, its band": ("-E", "75440", "-nu", "0.4999", "-shape", "cone", "-angle", "30",
                                        "-P", "74.71", "-order", "1", "-farfield", "clamped"),
}


@pytest.mark.parametrize("args", COLLAPSED.values(), ids=COLLAPSED.keys())
def test_a_contact_collapsed_to_the_axis_is_a_judged_run_with_its_files(solve, args, tmp_path):
    run = solve(*args, "-vtk", str(tmp_path / "f.vtu"))
    assert run.exit_code == 5, run.output
    s = run.summary
    assert s["status"] == "inaccurate" and "p1-locking" in s["warnings"]
    assert "film" not in run.stderr  # no warning names a film the scene does not have
    assert sorted(p.name for p in run.outdir.iterdir()) == RUN_FILES_2D
    assert len(run.table("axis")) > 1 and len(list(tmp_path.glob("f*.vtu"))) == 3


def test_no_output_is_written_through_a_planted_link(tmp_path):
    out, precious = tmp_path / "out", tmp_path / "precious.csv"
    out.mkdir()
    precious.write_text("precious\n")
    for name in ("summary.csv.part", "summary.csv", "f_near.vtu"):
        (out / name).symlink_to(precious)
    proc = run_limited(["-n", "8", "-out", str(out), "-vtk", str(out / "f.vtu")], file_kb=10**6)
    assert proc.returncode in (0, 5), proc.stderr
    assert precious.read_text() == "precious\n"
    # the run's files replace the links (a rename), and its parts folder is gone
    for name in ("summary.csv", "f_near.vtu"):
        assert not (out / name).is_symlink() and (out / name).stat().st_size > 1000, name
    assert not list(out.glob(".hertz-parts*"))


def test_a_run_into_a_folder_another_run_is_writing_has_parts_of_its_own(tmp_path):
    # two runs into one -out shared one parts folder: exit 8 with FreeFEM's trace, or a false "disk full"
    out, outside = tmp_path / "out", tmp_path / "outside"
    (out / ".hertz-parts.1").mkdir(parents=True)  # another run's, mid-write
    (out / ".hertz-parts.1" / "summary.csv").write_text("theirs\n")
    outside.mkdir()
    (out / ".hertz-parts.2").symlink_to(outside)  # planted
    stale = out / ".hertz-parts.9"  # a killed run's, two days old
    stale.mkdir()
    os.utime(stale, (time.time() - 2 * 86400,) * 2)
    proc = run_limited(["-n", "8", "-out", str(out), "-vtk", str(out / "f.vtu")], file_kb=10**6)
    assert proc.returncode in (0, 5), proc.stdout[-500:] + proc.stderr
    assert (out / "summary.csv").stat().st_size > 1000 and (out / "f.vtu").is_file()
    assert (out / ".hertz-parts.1" / "summary.csv").read_text() == "theirs\n" and not any(outside.iterdir())
    assert sorted(p.name for p in out.glob(".hertz-parts*")) == [".hertz-parts.1", ".hertz-parts.2"]


def test_a_run_that_is_no_answer_keeps_an_earlier_answer_and_its_own_files_apart(tmp_path):
    # a maxiter rerun's files replaced a converged run's; into an empty folder they are its data
    out = tmp_path / "out"
    first = run_limited(["-n", "8", "-out", str(out), "-vtk", str(out / "f.vtu")], file_kb=10**6)
    assert first.returncode == 0, first.stderr
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    again = run_limited(["-n", "8", "-E", "20", "-maxit", "1", "-out", str(out), "-vtk", str(out / "f.vtu")],
                        file_kb=10**6)
    assert again.returncode == 3 and "its files are in" in again.stderr, again.stderr
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before
    assert "maxiter" in (out / "unanswered" / "summary.csv").read_text()
    assert (out / "unanswered" / "f.vtu").is_file()
    fresh = run_limited(["-n", "8", "-E", "20", "-maxit", "1", "-out", str(tmp_path / "fresh")], file_kb=10**6)
    assert fresh.returncode == 3 and "maxiter" in (tmp_path / "fresh" / "summary.csv").read_text()
    # the next answer replaces both
    assert run_limited(["-n", "8", "-E", "20", "-out", str(out)], file_kb=10**6).returncode == 0
    assert not (out / "unanswered").exists() and (out / "summary.csv").read_bytes() != before["summary.csv"]


def test_a_failed_rerun_replaces_none_of_the_earlier_files(tmp_path):
    out = tmp_path / "out"
    first = run_limited(["-n", "8", "-out", str(out), "-vtk", str(out / "f.vtu")], file_kb=10**6)
    assert first.returncode in (0, 5), first.stderr
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    # a rerun of another scene whose VTK files do not fit: its CSV files must not land either
    proc = run_limited(["-n", "8", "-E", "20", "-out", str(out), "-vtk", str(out / "f.vtu")], file_kb=64)
    assert proc.returncode == 4 and "cannot write the" in proc.stderr, proc.stderr
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


@pytest.mark.parametrize("where", ["a folder named summary.csv", "/proc"])
def test_an_output_that_cannot_be_a_file_is_one_line_and_exit_4(tmp_path, where):
    out = tmp_path / "out"
    (out / "summary.csv").mkdir(parents=True)
    target = "/proc" if where == "/proc" else str(out)
    proc = run_limited(["-n", "8", "-out", target], file_kb=10**6)
    assert proc.returncode == 4, proc.stdout[-500:]
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hertz.edp: error: cannot write the output files"), proc.stderr
    assert (out / "summary.csv").is_dir() and not any((out / "summary.csv").iterdir())


def test_a_script_folder_with_a_semicolon_is_one_line_for_a_delegated_branch(tmp_path):
    # FF_LOADPATH splits its folders on ';': the delegated branch could not find its plugins
    import shutil

    from driver.layout import EDP_DIR
    folder = tmp_path / "semi;colon"
    shutil.copytree(EDP_DIR, folder, ignore=shutil.ignore_patterns("*.so", "*.o"))
    proc = subprocess.run(["FreeFem++", "-nw", "-v", "0", str(folder / "hertz.edp"), "-nu", "0.5", "-n", "4"],
                          cwd=folder, capture_output=True, text=True, env=freefem.freefem_env(), timeout=120)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "holds a ';'" in lines[0], proc.stderr


def _processes_naming(marker: str) -> list[int]:
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/cmdline", "rb") as f:
                    if marker.encode() in f.read():
                        found.append(int(entry))
            except OSError:
                pass
    return found


@pytest.mark.slow
def test_a_killed_run_leaves_no_delegated_solver_behind(tmp_path):
    marker = str(tmp_path / "orphan-check")
    proc = subprocess.Popen(freefem.command(["-model", "3d", "-n", "10", "-out", marker]),
                            env=freefem.freefem_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.time() + 60
        while time.time() < deadline and len(_processes_naming(marker)) < 2:
            time.sleep(0.1)  # the 3D branch runs in a child of this one
        assert len(_processes_naming(marker)) >= 2, "the 3D branch never started"
        proc.kill()
        proc.wait()
        deadline = time.time() + 10
        while time.time() < deadline and _processes_naming(marker):
            time.sleep(0.1)
        assert _processes_naming(marker) == []
    finally:
        for pid in _processes_naming(marker):
            os.kill(pid, 9)


def test_out_and_vtk_in_one_folder_named_two_ways_write_both(tmp_path):
    # -out out -vtk ./out/f.vtu: the VTK files' parts folder is -out's; made anew a second
    # time it dropped the CSV parts, and the run exited 4 with nothing written
    proc = subprocess.run(freefem.command(["-n", "8", "-out", "out", "-vtk", "./out/f.vtu"]), cwd=tmp_path,
                          capture_output=True, text=True, env=freefem.freefem_env(), timeout=300)
    assert proc.returncode in (0, 5), proc.stderr
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"summary.csv", "profile.csv", "f.vtu", "f_near.vtu", "f_surface.vtu"} <= names, names
    assert ".hertz-parts" not in names
