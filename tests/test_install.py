"""A non-editable install (pip install . into a fresh virtual environment) runs cases from any folder:
the wheel carries the solver scripts (setup.py copies edp/ into the package)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import driver

from conftest import copy_tracked


@pytest.fixture(scope="module")
def venv(tmp_path_factory):
    source = copy_tracked(tmp_path_factory.mktemp("clone"))
    env_dir = tmp_path_factory.mktemp("venv")
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(env_dir)], check=True)
    # the dependencies come from this machine's site-packages; the package itself is built and installed
    proc = subprocess.run([str(env_dir / "bin" / "pip"), "install", "-q", "--no-deps", str(source)],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    return env_dir


def outside_env() -> dict[str, str]:
    """An environment that points at no checkout or virtual environment: the installed package alone."""
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}


def test_the_installed_command_runs_a_case_from_another_folder(venv, tmp_path):
    proc = subprocess.run([str(venv / "bin" / "hertz"), "run", "--n", "8", "--json"], cwd=tmp_path,
                          capture_output=True, text=True, env=outside_env(), timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["status"] == "converged"
    assert (tmp_path / "results" / "runs" / "single" / "n=8" / "summary.csv").is_file()


SOLVE = """
import driver, driver.layout
from driver import solve
result = solve(n=8, method="lagrange")
print(driver.__file__, driver.layout.EDP_DIR, driver.__version__, result.status, result.files, sep="\\n")
"""


def test_solve_uses_the_solver_scripts_shipped_in_the_package(venv, tmp_path):
    proc = subprocess.run([str(venv / "bin" / "python"), "-c", SOLVE], cwd=tmp_path, capture_output=True,
                          text=True, env=outside_env(), timeout=300)
    assert proc.returncode == 0, proc.stderr
    package, edp, version, status, files = proc.stdout.split("\n")[:5]
    assert package.startswith(str(venv)) and edp == str(venv / "lib" / f"python{sys.version_info.major}."
                                                      f"{sys.version_info.minor}" / "site-packages" / "driver" / "edp")
    assert version == driver.__version__ and status == "converged" and files.startswith(str(tmp_path))


def test_a_read_only_install_builds_the_3d_plugin_in_the_users_cache(tmp_path):
    # a system install, a container or a shared image: the package folder takes no file. The
    # plugin was built into it at run time, and there every 3D run exited 2 blaming g++
    base = Path(tempfile.mkdtemp(dir="/tmp", prefix="hertz-ro-"))  # pytest's folders are root's alone
    try:
        base.chmod(0o755)
        package = base / "package"
        copy_tracked(package)
        cache = base / "user"
        cache.mkdir()
        script = f"cd {cache} && exec FreeFem++ -nw -v 0 {package}/edp/hertz.edp -model 3d -n 4 -out {cache}/out"
        env = dict(os.environ, HOME=str(cache), XDG_CACHE_HOME=str(cache / "cache"))
        if os.geteuid() == 0:  # root writes through any mode: run as nobody, who may not write there
            os.chown(cache, 65534, 65534)
            command = ["setpriv", "--reuid", "65534", "--regid", "65534", "--clear-groups", "sh", "-c", script]
        else:
            subprocess.run(["chmod", "-R", "a-w", str(package)], check=True)
            command = ["sh", "-c", script]
        proc = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)
        assert proc.returncode in (0, 5), proc.stdout[-1500:] + proc.stderr  # n = 4 may be inaccurate
        assert (cache / "out" / "summary.csv").is_file()
        assert not list((package / "edp" / "plugin").glob("*.so"))  # nothing written into the package
        assert len(list((cache / "cache" / "hertz-contact").glob("plugin-*/plugin/surfaceschur.so"))) == 1
    finally:
        subprocess.run(["chmod", "-R", "u+w", str(base)], check=False)
        shutil.rmtree(base, ignore_errors=True)
