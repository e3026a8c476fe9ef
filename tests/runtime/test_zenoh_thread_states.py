"""A Zenoh thread keeps its Python thread state from one robomodel callback to the next.

zenoh-python enters Python from its own threads through PyGILState_Ensure/Release, which made
and destroyed a thread state (and its frame stack) for every sample: about 20 us of each
message's way at 1 kHz. robomodel's callback wrapper keeps it.
Each case runs in a process of its own: a thread state kept by an earlier test in the same
process would stay kept.
"""

from __future__ import annotations

import json
import subprocess
import sys

from tests.conftest import unique_domain
from tests.timing import scaled

_SCRIPT = r"""
import ctypes, json, sys, threading, time
from robomodel.runtime import Context
from robomodel.runtime.transport._zenoh_common import direct, import_zenoh

api = ctypes.pythonapi
api.PyThreadState_Get.restype = ctypes.c_void_p
api.PyThreadState_GetID.argtypes = [ctypes.c_void_p]
api.PyThreadState_GetID.restype = ctypes.c_uint64
seen = {}
got = []

def record(_sample):
    state = api.PyThreadState_GetID(api.PyThreadState_Get())
    seen.setdefault(threading.get_ident(), set()).add(state)
    got.append(1)

bare = lambda f: import_zenoh().handlers.Callback(f, None, indirect=False)
handler = direct if sys.argv[2] == "wrapped" else bare
domain = int(sys.argv[1])
key = f"robomodel_test/{domain}/thread_states"
with Context("zenoh", domain_id=domain) as a, Context("zenoh", domain_id=domain) as b:
    sub = b.transport.session.declare_subscriber(key, handler(record))
    deadline = time.monotonic() + float(sys.argv[3])
    while len(got) < 40 and time.monotonic() < deadline:
        a.transport.session.put(key, b"x")
        time.sleep(0.005)  # one sample at a time: each callback ends before the next
    sub.undeclare()
assert threading.get_ident() not in seen, "delivered on the putting thread, not Zenoh's"
print(json.dumps({"samples": len(got), "states": [sorted(s) for s in seen.values()]}))
"""


def _thread_states(variant: str) -> list[list[int]]:
    """Each receiving thread's Python thread-state ids over 40 samples from another session."""
    budget = scaled(20.0)
    done = subprocess.run(
        [sys.executable, "-c", _SCRIPT, unique_domain(), variant, str(budget)],
        capture_output=True,
        text=True,
        timeout=budget + scaled(30.0),
        check=True,
    )
    result = json.loads(done.stdout.strip().splitlines()[-1])
    assert result["samples"] >= 40, result
    return result["states"]  # type: ignore[no-any-return]


def test_each_zenoh_thread_runs_every_callback_in_one_thread_state() -> None:
    states = _thread_states("wrapped")
    assert states and all(len(ids) == 1 for ids in states), states


def test_without_the_wrapper_each_callback_had_a_new_thread_state() -> None:
    """The control: zenoh-python's bare direct callback, as robomodel called it before."""
    states = _thread_states("bare")
    assert sum(len(ids) for ids in states) >= 40, states
