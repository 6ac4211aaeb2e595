"""numba's inliner makes a callee's IR once per function, not once per call site
(seahelm.simulation.inline_copy), and the compiled code stays numba's.

A generated loop inlines the MMG model's output function (and, through it, the forces and
their helpers) at three sites, as a kernel inlines a model's right-hand side at each stage of
RK4. Measured in fresh processes, one with ``SEAHELM_INLINE_COPY=0`` (numba's own inliner):
numba runs its untyped pipeline on a callee at every site, and copies every inlined IR twice
(once to inline, once kept unmutated and thrown away by the inlining pass).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

_SCRIPT = r"""
import hashlib, json, re
import numpy as np
import numba
from numba.core import inline_closurecall as icc, ir
from seahelm._codegen import exec_generated
from seahelm.parameters import as_records, stack_params
from seahelm.simulation import inline_copy
from seahelm.simulation.inlining import inline_always
from seahelm.vessels import mmg

counts = {"untyped": 0, "var_copies": 0}
untyped = icc.InlineWorker.run_untyped_passes
def counted_untyped(self, *a, **k):
    counts["untyped"] += 1
    return untyped(self, *a, **k)
icc.InlineWorker.run_untyped_passes = counted_untyped
var_copy = ir.Var.__deepcopy__
def counted_copy(self, memo):
    counts["var_copies"] += 1
    return var_copy(self, memo)
ir.Var.__deepcopy__ = counted_copy

text = '''
from numba import njit
FASTMATH = {"arcp", "contract", "afn", "reassoc"}
def make(g):
    @njit(fastmath=FASTMATH, _nrt=False)
    def loop(X, U, P, out):
        for i in range(X.shape[0]):
            g(0.0, X[i], U[i], P[i], out[3 * i])
            g(1.0, X[i], U[i], P[i], out[3 * i + 1])
            for j in range(2):
                U[i, j] *= 0.5
            g(2.0, X[i], U[i], P[i], out[3 * i + 2])
    return loop
'''
loop = exec_generated("seahelm_test_inline_memo_loop", text).make(inline_always(mmg.mmg_output))
P = as_records(stack_params([mmg.KVLCC2_L7, mmg.KVLCC2_L7]), mmg.MMGParams)
args = (np.array([[1.1, 0.05, 0.01, 0.0, 0.0, 0.2], [0.9, -0.1, 0.02, 1.0, 2.0, -0.3]]),
        np.array([[0.1, 10.0], [-0.2, 8.0]]), P, np.zeros((6, len(mmg.OUTPUTS))))
loop.compile(tuple(numba.typeof(a) for a in args))
loop(*args)
llvm = next(iter(loop.inspect_llvm().values()))
llvm = re.sub(r"RecordILi[0-9]+E", "RecordILiNE", llvm)  # numba's per-process type counter
# the numbers numba gives each inlined function (its FunctionIdentity's unique id) in the
# names of the values and of numba's own helpers' symbols (B<n>v<id>B<m> and m characters)
llvm = re.sub(r"_v[0-9]+_", "_v_", llvm)
parts, i = [], 0
for m in re.finditer(r"B([0-9]+)v[0-9]+B([0-9]+)", llvm):
    if m.start() >= i:
        parts += [llvm[i:m.start()], "<tag>"]
        i = m.end() + int(m.group(2))
llvm = "".join(parts + [llvm[i:]])
# and numba's block labels (a global counter that each untyped pipeline run advances):
# renamed in order of appearance, with the padding of LLVM's comments after them
seen = {}
llvm = re.sub(r"(?<![A-Za-z0-9_$])B([0-9]+)(?=[.:, \]\n])",
              lambda m: "B#%d" % seen.setdefault(m.group(1), len(seen)), llvm)
llvm = re.sub(r" +;", " ;", llvm)
print(json.dumps({"installed": inline_copy.installed(), **counts,
                  "llvm": hashlib.sha256(llvm.encode()).hexdigest(),
                  "out": args[-1].tolist()}))
"""


def _run(patch: bool) -> dict:
    # (one hash seed: numba's symbol names spell the fastmath flags, a set, in hash order)
    env = {**os.environ, "SEAHELM_INLINE_COPY": "1" if patch else "0", "PYTHONHASHSEED": "0"}
    proc = subprocess.run([sys.executable, "-c", _SCRIPT], env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def test_a_callee_inlined_at_three_sites_is_made_once_and_compiles_the_same() -> None:
    numba_own, patched = _run(False), _run(True)
    assert not numba_own["installed"] and patched["installed"]
    # the compiled loop: the same LLVM IR but for the numbers in names and block labels, so
    # the same numbers
    assert patched["llvm"] == numba_own["llvm"]
    assert patched["out"] == numba_own["out"]
    assert all(any(v != 0.0 for v in row) for row in patched["out"])
    # numba: the output function's IR made at each of the 3 sites, and everything it inlines
    # with it; here once (before: 3 times as many runs of the untyped pipeline, or more)
    assert patched["untyped"] * 3 <= numba_own["untyped"], (patched, numba_own)
    assert patched["var_copies"] * 3 < numba_own["var_copies"], (patched, numba_own)
