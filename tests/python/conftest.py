"""pytest set-up of the Python package's tests (tests/python.cmake runs them with
PYTHONPATH on the build tree's package and RODNET_CLI the build's command)."""
import os
import subprocess

import pytest

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(SOURCE, "problems", "scenes")


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("RODNET_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("RODNET_CLI (the rodnet command) not set")
    return path


@pytest.fixture(scope="session")
def scenes():
    return SCENES


@pytest.fixture(scope="session")
def hc8(cli, tmp_path_factory):
    """A periodic honeycomb cell with rigid joints, 8 edges per strut."""
    out = str(tmp_path_factory.mktemp("cells") / "hc8.json")
    subprocess.run([cli, "generate", "honeycomb", "--periodic", "--joint-model", "rigid",
                    "--edges-per-rod", "8", "--slenderness", "0.05", "-o", out],
                   check=True, capture_output=True)
    return out
