# Shared fixtures of the rscene Python tests: where the repository, the
# built tools and the scenes are.  `make test` runs these with
# PYTHONPATH=build/python and RSCENE_BIN=build/bin.
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BIN = pathlib.Path(os.environ.get("RSCENE_BIN", ROOT / "build" / "bin"))
EXAMPLES = sorted((ROOT / "examples").glob("*.rscene"))
CORPUS = sorted((ROOT / ".." / "shared" / "corpus").glob("*.rscene"))


def corpus_scene(name):
    """A scene of the shared corpus (../shared/corpus, else
    /work/shared/corpus); skips the test where neither is."""
    for folder in (ROOT / ".." / "shared" / "corpus", pathlib.Path("/work/shared/corpus")):
        if (folder / name).is_file():
            return folder / name
    pytest.skip("the shared corpus (%s) is not here" % name)


def tool(name, *args, check=True, stdin=None):
    """Runs a built tool; returns (exit status, stdout bytes)."""
    exe = BIN / name
    if not exe.exists():
        pytest.skip("%s is not built in %s" % (name, BIN))
    p = subprocess.run([str(exe), *map(str, args)], input=stdin, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, timeout=120)
    if check and p.returncode not in (0, 1):
        raise AssertionError("%s failed (%d): %s" % (name, p.returncode, p.stderr.decode()))
    return p.returncode, p.stdout
