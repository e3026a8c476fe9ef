"""Kinematics benchmarks beside the references (pinocchio, yourdfpy, ikpy), in one run.

Run: ``.venv/bin/python bench/bench_kinematics.py`` (``--targets 1000 --ikpy-targets 1000``).

1. Batched FK, 10,000 Panda configurations, every link: ``Kinematics.fk(Q)`` against a
   pinocchio Python loop producing the same ``(10000, 13, 4, 4)`` array
   (``framesForwardKinematics`` and each link's ``oMf``), and against the bare loop.
2. One configuration (Panda, UR5): ``fk(q)`` against pinocchio's ``framesForwardKinematics``
   (placements not copied out), ``fk_link`` against ``framesForwardKinematics`` + that frame's
   ``oMf[...].homogeneous``, ``jacobian`` against our own ``fk`` and against pinocchio's
   ``computeFrameJacobian``; each pair interleaved, the median per-round ratio printed, for
   both backends (``auto``: MuJoCo when installed; ``numpy``: the reference).
3. IK on Panda (``panda_hand_tcp``) and UR5 (``ee_link``) over random reachable targets
   (FK of uniform random configurations inside the limits): success within 1e-6 m and
   1e-6 rad (checked by our FK), median and p90 time per target, against the same damped
   least-squares loop on pinocchio (same damping, step clamp, limits, restarts, iteration
   budget; ``computeJointJacobians`` + ``getFrameJacobian`` + ``log3``), the two solvers alternating target by
   target; the batched form's solves per second; ikpy's ``inverse_kinematics``
   (orientation_mode="all") on the same targets.
4. Scaling: one configuration's ``fk`` on synthetic chains of 10, 100 and 1,000 links
   against pinocchio's ``framesForwardKinematics``.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
import warnings
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data, synthetic_chain_urdf, time_call, time_interleaved
from robomodel.description import read_urdf
from robomodel.kinematics import Kinematics
from robomodel.kinematics.ik import _DAMPING, _MAX_ITERATIONS, _MAX_STEP_RAD
from robomodel.kinematics.se3 import log_rotation

PANDA = str(example_robot_data("panda_description/urdf/panda.urdf"))
UR5 = str(example_robot_data("ur_description/urdf/ur5_robot.urdf"))


def _reached(kin: Kinematics, link: str, q: np.ndarray, T: np.ndarray) -> bool:
    if not bool(kin.within_limits(q, tol=1e-12)):
        return False
    T_q = kin.fk_link(q, link)
    pos = float(np.linalg.norm(T_q[:3, 3] - T[:3, 3]))
    rot = float(np.linalg.norm(log_rotation(T[:3, :3] @ T_q[:3, :3].T)))
    return pos <= 1e-6 and rot <= 1e-6


def bench_fk_batch(kin: Kinematics, n: int = 10_000) -> None:
    import pinocchio

    model = pinocchio.buildModelFromUrdf(PANDA)
    data = model.createData()
    Q = kin.random_q(n, seed=0)
    # Our q is pinocchio's q with the mimic finger appended (panda_finger_joint2 = joint1).
    Qp = np.concatenate([Q, Q[:, -1:]], axis=1)
    fids = [model.getFrameId(name, pinocchio.BODY) for name in kin.link_names]

    def pin_all_links() -> np.ndarray:
        out = np.empty((n, len(fids), 4, 4))
        for k in range(n):
            pinocchio.framesForwardKinematics(model, data, Qp[k])
            for j, fid in enumerate(fids):
                out[k, j] = data.oMf[fid].homogeneous
        return out

    def pin_bare() -> None:
        for k in range(n):
            pinocchio.framesForwardKinematics(model, data, Qp[k])

    ours = time_call(lambda: kin.fk(Q), repeat=7)
    ours_contiguous = time_call(lambda: np.ascontiguousarray(kin.fk(Q)), repeat=7)
    pin_full = time_call(pin_all_links, repeat=3, min_time_s=0.0)
    pin_loop = time_call(pin_bare, repeat=3, min_time_s=0.0)
    np.testing.assert_allclose(kin.fk(Q[:50]), pin_all_links()[:50], atol=1e-10)
    print(f"\n## Batched FK: {n} Panda configurations, all {len(fids)} links\n")
    print("| implementation | time | configurations/s | robomodel speed-up |")
    print("|---|---|---|---|")
    for label, t in [
        ("robomodel `fk(Q)` (read-only view)", ours),
        ("robomodel `fk(Q)` + `np.ascontiguousarray`", ours_contiguous),
        ("pinocchio loop, all link poses copied out", pin_full),
        ("pinocchio loop, `framesForwardKinematics` only", pin_loop),
    ]:
        print(f"| {label} | {t * 1e3:.2f} ms | {n / t / 1e6:.2f} M | {t / ours:.1f}x |")


def _pin_q(kin: Kinematics, model: object, q: np.ndarray) -> np.ndarray:
    """pinocchio's q for ours (Panda: the mimic finger appended; UR5: the same)."""
    nq = model.nq  # type: ignore[attr-defined]
    return q if nq == len(q) else np.append(q, q[-1])


def bench_fk_single(name: str, path: str, link: str, rounds: int) -> None:
    import pinocchio

    model = pinocchio.buildModelFromUrdf(path)
    data = model.createData()
    fid = model.getFrameId(link, pinocchio.BODY)
    robot = read_urdf(path).robot
    print(f"\n## One {name} configuration ({len(robot.links)} links; link `{link}`)\n")
    print("| backend | measurement | robomodel | reference | reference time | ratio |")
    print("|---|---|---|---|---|---|")
    for backend in ("auto", "numpy"):
        kin = Kinematics(robot, backend=backend)  # type: ignore[arg-type]
        q = kin.random_q(seed=1)
        qp = _pin_q(kin, model, q)
        pinocchio.framesForwardKinematics(model, data, qp)
        np.testing.assert_allclose(kin.fk_link(q, link), data.oMf[fid].homogeneous, atol=1e-10)
        label = f"{backend} ({kin.backend})"
        for what, ours, ref_name, ref in _single_cases(kin, q, link, model, data, qp, fid):
            t_ours, t_ref, ratio = time_interleaved(ours, ref, rounds=rounds)
            print(
                f"| {label} | {what} | {t_ours * 1e6:.2f} us | {ref_name} | "
                f"{t_ref * 1e6:.2f} us | {ratio:.2f}x |"
            )


def _single_cases(
    kin: Kinematics, q: np.ndarray, link: str, model: Any, data: Any, qp: np.ndarray, fid: int
) -> list[tuple[str, Callable[[], object], str, Callable[[], object]]]:
    import pinocchio

    def pin_fk() -> None:
        pinocchio.framesForwardKinematics(model, data, qp)

    def pin_fk_link() -> np.ndarray:
        pinocchio.framesForwardKinematics(model, data, qp)
        return data.oMf[fid].homogeneous  # type: ignore[no-any-return]

    def pin_jacobian() -> np.ndarray:
        return pinocchio.computeFrameJacobian(  # type: ignore[no-any-return]
            model, data, qp, fid, pinocchio.LOCAL_WORLD_ALIGNED
        )

    return [
        ("`fk(q)`, all links", lambda: kin.fk(q), "pinocchio `framesForwardKinematics`", pin_fk),
        (
            "`fk_link(q, link)`",
            lambda: kin.fk_link(q, link),
            "pinocchio `framesForwardKinematics` + `oMf[f].homogeneous`",
            pin_fk_link,
        ),
        (
            "`jacobian(q, link)`",
            lambda: kin.jacobian(q, link),
            "robomodel `fk(q)`",
            lambda: kin.fk(q),
        ),
        (
            "`jacobian(q, link)`",
            lambda: kin.jacobian(q, link),
            "pinocchio `computeFrameJacobian`",
            pin_jacobian,
        ),
    ]


def bench_fk_yourdfpy(kin: Kinematics) -> None:
    import yourdfpy

    urdf = yourdfpy.URDF.load(PANDA, load_meshes=False, build_collision_scene_graph=False)
    names = list(kin.link_names)
    q = kin.random_q(seed=1)

    def ydp() -> None:
        urdf.update_cfg(q[:8])
        for name in names:
            urdf.get_transform(name)

    t_ours, t_ref, ratio = time_interleaved(lambda: kin.fk(q), ydp, rounds=7)
    print(
        f"\n(Panda, all links: robomodel `fk(q)` {t_ours * 1e6:.2f} us, yourdfpy `update_cfg` + "
        f"`get_transform` per link {t_ref * 1e6:.2f} us: {1 / ratio:.1f}x faster)"
    )


def bench_fk_scaling(rounds: int) -> None:
    """pinocchio only up to 100 links: its ``Data`` for a 300-joint chain takes 1.8 GB, and
    for 1,000 joints more than the machine's 24 GB (it was killed by the OOM killer)."""
    import pinocchio

    print("\n## Scaling: one configuration, all links, synthetic chains\n")
    print(
        "| links | robomodel `fk(q)` auto | numpy | pinocchio `framesForwardKinematics` "
        "| auto / pinocchio | numpy / pinocchio |"
    )
    print("|---|---|---|---|---|---|")
    for n in (10, 100, 1000):
        text = synthetic_chain_urdf(n)
        robot = read_urdf(text).robot
        fast = Kinematics(robot)
        ref = Kinematics(robot, backend="numpy")
        q = fast.random_q(seed=0)
        np.testing.assert_allclose(fast.fk(q), ref.fk(q), atol=1e-9)
        if n <= 100:
            model = pinocchio.buildModelFromXML(text)
            pin_fk = partial(pinocchio.framesForwardKinematics, model, model.createData(), q)
            t_fast, t_pin, r_fast = time_interleaved(partial(fast.fk, q), pin_fk, rounds=rounds)
            t_np, _, r_np = time_interleaved(partial(ref.fk, q), pin_fk, rounds=rounds)
            pin_text, ratios = f"{t_pin * 1e6:.1f} us", f"{r_fast:.1f}x | {r_np:.1f}x"
        else:
            t_fast, t_np, _ = time_interleaved(
                partial(fast.fk, q), partial(ref.fk, q), rounds=rounds
            )
            pin_text, ratios = "- (Data > 24 GB)", "- | -"
        print(f"| {n} | {t_fast * 1e6:.1f} us | {t_np * 1e6:.1f} us | {pin_text} | {ratios} |")


def _ikpy_chain(name: str) -> tuple[object, list[int]]:
    from ikpy.chain import Chain

    if name == "panda":
        elements = ["panda_link0"]
        for i in range(1, 8):
            elements += [f"panda_joint{i}", f"panda_link{i}"]
        elements += ["panda_joint8", "panda_link8", "panda_hand_joint", "panda_hand"]
        elements += ["panda_hand_tcp_joint", "panda_hand_tcp"]
        chain = Chain.from_urdf_file(PANDA, base_elements=elements)
    else:
        chain = Chain.from_urdf_file(UR5, base_elements=["world"])
    active = [k for k, link in enumerate(chain.links) if link.joint_type != "fixed"]
    mask = [k in active for k in range(len(chain.links))]
    chain.active_links_mask = np.array(mask)
    return chain, active


class PinocchioDLS:
    """robomodel's single-target IK algorithm with pinocchio computing the pose and the
    Jacobian (``computeJointJacobians``, ``updateFramePlacement``, ``getFrameJacobian``
    LOCAL_WORLD_ALIGNED) and the rotation error (``log3``): same start, damping, step clamp,
    limit clamp, stall test, restarts and iteration budget, and the same numpy code around
    them. The 6x6 damped system is solved with ``np.linalg.solve`` (as in pinocchio's own IK
    example); robomodel's MuJoCo path uses MuJoCo's dense Cholesky for it instead."""

    def __init__(self, kin: Kinematics, path: str, link: str) -> None:
        import pinocchio

        self.pin = pinocchio
        self.model = pinocchio.buildModelFromUrdf(path)
        self.data = self.model.createData()
        self.fid = self.model.getFrameId(link, pinocchio.BODY)
        solver = kin._ik_solver(link, False)
        # The path's joints: robomodel's active q entries are pinocchio's first ones here
        # (revolute, one q and one v each; the Panda fingers come last).
        self.active = np.asarray(solver.chain.active)
        self.lower, self.upper = solver.lower, solver.upper
        self.sample_lo, self.sample_hi = solver.sample_lo, solver.sample_hi
        self.start = _pin_q(kin, self.model, np.asarray(solver.start))
        self.eye = np.eye(6)

    def solve(self, T_t: np.ndarray, rng: int, max_iterations: int = 3000, restarts: int = 50):
        pin, model, data, fid = self.pin, self.model, self.data, self.fid
        world = pin.LOCAL_WORLD_ALIGNED
        active, lower, upper, eye = self.active, self.lower, self.upper, self.eye
        R_t, p_t = T_t[:3, :3], T_t[:3, 3]
        q = self.start.copy()
        gen = None
        best_q, best = q.copy(), (math.inf, math.inf)
        total = attempts = 0
        while attempts <= restarts and total < max_iterations:
            attempts += 1
            qa = q[active]
            stall = 0
            last_cost = math.inf
            for _ in range(min(_MAX_ITERATIONS, max_iterations - total)):
                total += 1
                pin.computeJointJacobians(model, data, q)
                M = pin.updateFramePlacement(model, data, fid)
                J = pin.getFrameJacobian(model, data, fid, world)[:, active]
                ep = p_t - M.translation
                er = pin.log3(R_t @ M.rotation.T)
                e = np.concatenate((ep, er))
                pe = math.sqrt(float(ep @ ep))
                re = math.sqrt(float(er @ er))
                cost = pe + re
                if cost < best[0] + best[1]:
                    best_q, best = q.copy(), (pe, re)
                if pe <= 1e-6 and re <= 1e-6:
                    return best_q, True, total
                stall = stall + 1 if cost > 0.999 * last_cost else 0
                if stall >= 5:
                    break
                last_cost = cost
                damping = _DAMPING * float(e @ e) + 1e-9
                dq = J.T @ np.linalg.solve(J @ J.T + damping * eye, e)
                biggest = float(abs(dq).max())
                if biggest > _MAX_STEP_RAD:
                    dq *= _MAX_STEP_RAD / biggest
                qa = qa + dq
                np.maximum(qa, lower, out=qa)
                np.minimum(qa, upper, out=qa)
                q[active] = qa
            if gen is None:
                gen = np.random.default_rng(rng)
            q[active] = gen.uniform(self.sample_lo, self.sample_hi)
        return best_q, False, total


def _eval_comparison(kin: Kinematics, ref: PinocchioDLS, link: str) -> str:
    """One iteration's error + Jacobian, ours against pinocchio's, interleaved (a target
    0.05 rad per joint away: the rotation error is far from pi, as in most iterations)."""
    solver = kin._ik_solver(link, False)
    q = kin.random_q(seed=5)
    T_t = kin.fk_link(np.clip(q + 0.05, kin.lower, kin.upper), link)
    qp = _pin_q(kin, ref.model, q)
    pin, model, data, fid, active = ref.pin, ref.model, ref.data, ref.fid, ref.active
    R_t, p_t = np.ascontiguousarray(T_t[:3, :3]), T_t[:3, 3].copy()

    def pin_eval() -> None:
        pin.computeJointJacobians(model, data, qp)
        M = pin.updateFramePlacement(model, data, fid)
        pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)[:, active]
        ep = p_t - M.translation
        er = pin.log3(R_t @ M.rotation.T)
        np.concatenate((ep, er))
        math.sqrt(float(ep @ ep)) + math.sqrt(float(er @ er))

    ours, theirs, ratio = time_interleaved(
        lambda: solver.error_and_jacobian(q, R_t, p_t), pin_eval, rounds=11
    )
    return (
        f"one iteration's error + Jacobian: robomodel ({solver.backend}) {ours * 1e6:.2f} us, "
        f"pinocchio {theirs * 1e6:.2f} us, ratio {ratio:.2f}x"
    )


def bench_ik(name: str, path: str, link: str, n: int, n_ikpy: int) -> None:
    kin = Kinematics(read_urdf(path).robot)
    targets = kin.fk(kin.random_q(n, seed=42), links=[link])[:, 0]
    kin.ik(targets[0], link, rng=0)  # build and cache the solver
    ref = PinocchioDLS(kin, path, link)
    # The pinocchio loop's pose is checked against ours.
    q0 = kin.random_q(seed=3)
    ref.pin.computeJointJacobians(ref.model, ref.data, _pin_q(kin, ref.model, q0))
    M = ref.pin.updateFramePlacement(ref.model, ref.data, ref.fid)
    np.testing.assert_allclose(M.homogeneous, kin.fk_link(q0, link), atol=1e-10)
    J = ref.pin.getFrameJacobian(ref.model, ref.data, ref.fid, ref.pin.LOCAL_WORLD_ALIGNED)
    np.testing.assert_allclose(J[:, ref.active], kin.jacobian(q0, link)[:, ref.active], atol=1e-10)
    times, ok, iters = [], 0, []
    pin_times, pin_ok, pin_iters = [], 0, []
    for k, T in enumerate(targets):
        start = time.perf_counter()
        result = kin.ik(T, link, rng=k)
        middle = time.perf_counter()
        q_pin, success, count = ref.solve(T, rng=k)
        end = time.perf_counter()
        times.append(middle - start)
        pin_times.append(end - middle)
        ok += result.success and _reached(kin, link, np.asarray(result.q), T)
        iters.append(result.iterations)
        pin_ok += success and _reached(kin, link, q_pin[: kin.n_q], T)
        pin_iters.append(count)
    eval_line = _eval_comparison(kin, ref, link)
    start = time.perf_counter()
    batch = kin.ik_batch(targets, link, rng=0)
    batch_time = time.perf_counter() - start
    batch_ok = sum(
        bool(s) and _reached(kin, link, q, T)
        for s, q, T in zip(batch.success, batch.q, targets, strict=True)
    )
    rows = [
        (
            f"robomodel `ik` ({kin.backend})",
            n,
            ok / n,
            statistics.median(times),
            float(np.percentile(times, 90)),
            n / sum(times),
        ),
        (
            "same DLS loop on pinocchio",
            n,
            pin_ok / n,
            statistics.median(pin_times),
            float(np.percentile(pin_times, 90)),
            n / sum(pin_times),
        ),
        ("robomodel `ik_batch`", n, batch_ok / n, float("nan"), float("nan"), n / batch_time),
    ]
    ratios = [a / b for a, b in zip(times, pin_times, strict=True)]
    summary = (
        f"robomodel `ik`: median {statistics.median(iters):.0f} iterations, "
        f"pinocchio loop: median {statistics.median(pin_iters):.0f}; "
        f"median time ratio robomodel / pinocchio {statistics.median(times) / statistics.median(pin_times):.2f}x "
        f"(median of per-target ratios {statistics.median(ratios):.2f}x)"
    )
    if n_ikpy:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            chain, active = _ikpy_chain(name)
            ikpy_times, ikpy_ok = [], 0
            for T in targets[:n_ikpy]:
                start = time.perf_counter()
                sol = chain.inverse_kinematics(  # type: ignore[attr-defined]
                    target_position=T[:3, 3], target_orientation=T[:3, :3], orientation_mode="all"
                )
                ikpy_times.append(time.perf_counter() - start)
                q = kin.neutral()
                q[: len(active)] = np.asarray(sol)[active][: kin.n_q]
                ikpy_ok += _reached(kin, link, q, T)
        rows.append(
            (
                "ikpy `inverse_kinematics`",
                n_ikpy,
                ikpy_ok / n_ikpy,
                statistics.median(ikpy_times),
                float(np.percentile(ikpy_times, 90)),
                n_ikpy / sum(ikpy_times),
            )
        )
    print(f"\n## IK: {name} `{link}`, random reachable targets, tolerance 1e-6 m / 1e-6 rad\n")
    print("| solver | targets | success | median | p90 | solves/s |")
    print("|---|---|---|---|---|---|")
    for label, count, rate, med, p90, per_s in rows:
        med_text = "-" if med != med else f"{med * 1e3:.3f} ms"
        p90_text = "-" if p90 != p90 else f"{p90 * 1e3:.3f} ms"
        print(f"| {label} | {count} | {rate * 100:.1f}% | {med_text} | {p90_text} | {per_s:.0f} |")
    print(f"\n({summary})")
    print(f"\n({eval_line})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument("--ikpy-targets", type=int, default=1000)
    parser.add_argument("--rounds", type=int, default=21, help="interleaved rounds per timing")
    parser.add_argument("--skip", nargs="*", default=[], choices=["fk", "ik", "scaling"])
    args = parser.parse_args()
    import numpy
    import pinocchio

    print(f"# Kinematics benchmarks (numpy {numpy.__version__}, pinocchio {pinocchio.__version__})")
    panda = Kinematics(read_urdf(PANDA).robot)
    if "fk" not in args.skip:
        bench_fk_batch(panda)
        bench_fk_single("Panda", PANDA, "panda_hand_tcp", args.rounds)
        bench_fk_single("UR5", UR5, "ee_link", args.rounds)
        bench_fk_yourdfpy(panda)
    if "scaling" not in args.skip:
        bench_fk_scaling(args.rounds)
    if "ik" not in args.skip:
        bench_ik("panda", PANDA, "panda_hand_tcp", args.targets, args.ikpy_targets)
        bench_ik("ur5", UR5, "ee_link", args.targets, args.ikpy_targets)


if __name__ == "__main__":
    main()
