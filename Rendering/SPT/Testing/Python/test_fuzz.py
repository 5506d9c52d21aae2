"""Random meshes (random points, random and invalid connectivity, random cell types, random
arrays with NaN and Inf, random selections and transfer functions) rendered with each mapper,
many fixed seeds: no crash, no hang, and every render either draws, or reports a clear error
or warning, or had nothing to show (see fuzz_worker.py for what that means), with the input
unchanged.

The renders run in a subprocess (fuzz_worker.py), so that a crash fails this test with the
seed it happened at instead of killing pytest. Reproduce one seed with
`python3 Rendering/SPT/Testing/Python/fuzz_worker.py MAPPER SEED 1` under xvfb-run, with the
package and Testing/Python on PYTHONPATH.
"""

import os
import pathlib
import subprocess
import sys

import pytest

WORKER = pathlib.Path(__file__).resolve().parent / "fuzz_worker.py"
SEEDS = 400
TIMEOUT = 600  # seconds for all seeds of one mapper; measured: about 10 on two shared cores


def run_worker(kind: str, first: int, count: int) -> subprocess.CompletedProcess:
    env = os.environ.copy()
    env["PYTHONPATH"] = os.pathsep.join([str(WORKER.parent), env.get("PYTHONPATH", "")])
    return subprocess.run([sys.executable, str(WORKER), kind, str(first), str(count)],
                          capture_output=True, text=True, env=env, timeout=TIMEOUT, check=False)


def outcomes(stdout: str):
    """{seed: outcome} of the seeds that finished, the seeds that failed a check (with why),
    and the last seed begun."""
    done, failed, last = {}, {}, None
    for line in stdout.splitlines():
        word, _, rest = line.partition(" ")
        seed, _, detail = rest.partition(" ")
        if word == "begin":
            last = int(seed)
        elif word == "end":
            done[int(seed)] = detail
        elif word == "fail":
            failed[int(seed)] = detail
    return done, failed, last


@pytest.mark.parametrize("kind", ["spt", "havs", "pbvr"])
def test_random_meshes(kind, have_display):
    try:
        result = run_worker(kind, 0, SEEDS)
    except subprocess.TimeoutExpired as timeout:
        _, _, last = outcomes(timeout.stdout.decode() if timeout.stdout else "")
        pytest.fail(f"{kind}: no answer within {TIMEOUT} s, at seed {last}")
    done, failed, last = outcomes(result.stdout)
    if result.returncode not in (0, 1) or (last is not None and last not in done and
                                           last not in failed):
        tail = "\n".join(result.stderr.splitlines()[-5:])
        pytest.fail(f"{kind}: the worker died (status {result.returncode}) at seed {last}:\n{tail}")
    assert not failed, f"{kind}: checks failed at seeds {failed}"
    assert len(done) == SEEDS
    # The inputs were random enough to reach every outcome, drawing among them.
    counts = {outcome: list(done.values()).count(outcome) for outcome in set(done.values())}
    assert counts.get("drew", 0) >= 10 and counts.get("error", 0) >= 10, counts
