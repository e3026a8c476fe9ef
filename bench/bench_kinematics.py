"""Kinematics benchmarks beside the references (pinocchio, yourdfpy, ikpy), in one run.

Run: ``.venv/bin/python bench/bench_kinematics.py`` (``--targets 1000 --ikpy-targets 1000``).

1. Batched FK, 10,000 Panda configurations, every link: ``Kinematics.fk(Q)`` against a
   pinocchio Python loop producing the same ``(10000, 13, 4, 4)`` array
   (``framesForwardKinematics`` and each link's ``oMf``), and against the bare loop.
2. One Panda configuration, every link: ``Kinematics.fk(q)`` against pinocchio's
   ``framesForwardKinematics`` (placements not copied out) and yourdfpy.
3. IK on Panda (``panda_hand_tcp``) and UR5 (``ee_link``) over random reachable targets
   (FK of uniform random configurations inside the limits): success within 1e-6 m and
   1e-6 rad (checked by our FK), median and p90 time per target; the batched form's solves
   per second; ikpy's ``inverse_kinematics`` (orientation_mode="all") on the same targets.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data, time_call
from robomodel.description import read_urdf
from robomodel.kinematics import Kinematics
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


def bench_fk_single(kin: Kinematics) -> None:
    import pinocchio

    model = pinocchio.buildModelFromUrdf(PANDA)
    data = model.createData()
    q = kin.random_q(seed=1)
    qp = np.append(q, q[-1])
    ours = time_call(lambda: kin.fk(q))
    pin = time_call(lambda: pinocchio.framesForwardKinematics(model, data, qp))
    rows = [("robomodel `fk(q)`", ours), ("pinocchio `framesForwardKinematics`", pin)]
    try:
        import yourdfpy

        urdf = yourdfpy.URDF.load(PANDA, load_meshes=False, build_collision_scene_graph=False)
        names = list(kin.link_names)
        cfg = q[:8]

        def ydp() -> None:
            urdf.update_cfg(cfg)
            for name in names:
                urdf.get_transform(name)

        rows.append(("yourdfpy `update_cfg` + `get_transform` per link", time_call(ydp)))
    except Exception as exc:  # a reference that fails is reported, not fatal
        print(f"(yourdfpy skipped: {exc})")
    print(f"\n## One Panda configuration, all {len(kin.link_names)} links\n")
    print("| implementation | time per call |")
    print("|---|---|")
    for label, t in rows:
        print(f"| {label} | {t * 1e6:.2f} us |")


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


def bench_ik(name: str, path: str, link: str, n: int, n_ikpy: int) -> None:
    kin = Kinematics(read_urdf(path).robot)
    targets = kin.fk(kin.random_q(n, seed=42), links=[link])[:, 0]
    kin.ik(targets[0], link, rng=0)  # build and cache the solver
    times, ok, iters = [], 0, []
    for k, T in enumerate(targets):
        start = time.perf_counter()
        result = kin.ik(T, link, rng=k)
        times.append(time.perf_counter() - start)
        ok += result.success and _reached(kin, link, np.asarray(result.q), T)
        iters.append(result.iterations)
    start = time.perf_counter()
    batch = kin.ik_batch(targets, link, rng=0)
    batch_time = time.perf_counter() - start
    batch_ok = sum(
        bool(s) and _reached(kin, link, q, T)
        for s, q, T in zip(batch.success, batch.q, targets, strict=True)
    )
    rows = [
        (
            "robomodel `ik`",
            n,
            ok / n,
            statistics.median(times),
            float(np.percentile(times, 90)),
            n / sum(times),
        ),
        ("robomodel `ik_batch`", n, batch_ok / n, float("nan"), float("nan"), n / batch_time),
    ]
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
    print(f"\n(robomodel `ik`: median {statistics.median(iters):.0f} iterations)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument("--ikpy-targets", type=int, default=1000)
    parser.add_argument("--skip", nargs="*", default=[], choices=["fk", "ik"])
    args = parser.parse_args()
    import numpy
    import pinocchio

    print(f"# Kinematics benchmarks (numpy {numpy.__version__}, pinocchio {pinocchio.__version__})")
    panda = Kinematics(read_urdf(PANDA).robot)
    if "fk" not in args.skip:
        bench_fk_batch(panda)
        bench_fk_single(panda)
    if "ik" not in args.skip:
        bench_ik("panda", PANDA, "panda_hand_tcp", args.targets, args.ikpy_targets)
        bench_ik("ur5", UR5, "ee_link", args.targets, args.ikpy_targets)


if __name__ == "__main__":
    main()
