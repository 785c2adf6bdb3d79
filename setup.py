"""Build hook: a non-editable install carries the solver scripts inside the package.

The wheel gets edp/ as driver/edp/, where driver.layout looks for it when there
is no checkout around the package. An editable install uses the checkout's edp/
directly and copies nothing. Everything else is in pyproject.toml.
"""
import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

SOURCE = Path(__file__).resolve().parent / "edp"
# what the sdist leaves out of edp/ (MANIFEST.in's global-exclude) the wheel leaves out too
EXCLUDED = next(line.split()[1:] for line in (SOURCE.parent / "MANIFEST.in").read_text().splitlines()
                if line.startswith("global-exclude"))


class BuildWithSolver(build_py):
    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        target = Path(self.build_lib) / "driver" / "edp"
        shutil.rmtree(target, ignore_errors=True)
        shutil.copytree(SOURCE, target, ignore=shutil.ignore_patterns(*EXCLUDED))


setup(cmdclass={"build_py": BuildWithSolver})
