"""A peer flooding the graph with liveliness tokens hides nobody else's entities,
is bounded with one warning and a non-zero exit, and the memory goes when its tokens go."""

from __future__ import annotations

import logging
import os
import subprocess
import sys
import textwrap
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import pytest

from tests.conftest import ROBOMODEL, ROOT, ToolResult, free_port, unique_domain
from tests.timing import scaled, wait_until

pytest.importorskip("zenoh")

STRING = "std_msgs::msg::dds_::String_/RIHS01_x/::,7:,:,:,,"


def _token_keys(domain: str, zid: str, node: str, topics: list[str]) -> list[str]:
    keys = [f"@ros2_lv/{domain}/{zid}/0/0/NN/%/%/{node}"]
    keys += [
        f"@ros2_lv/{domain}/{zid}/0/{i + 1}/MP/%/%/{node}/%{topic}/{STRING}"
        for i, topic in enumerate(topics)
    ]
    return keys


@contextmanager
def _peer(keys: list[str]) -> Iterator[tuple[Any, list[Any]]]:
    """A Zenoh session of its own (one peer) declaring ``keys`` as liveliness tokens."""
    from robomodel.runtime.transport._zenoh_common import close_session, undeclare_all
    from robomodel.runtime.transport._zenoh_session import open_session

    session = open_session().session
    tokens: list[Any] = []
    try:
        tokens += [session.liveliness().declare_token(key) for key in keys]
        yield session, tokens
    finally:
        # undeclared before the session closes, as a node that ends undeclares its entities:
        # a closed session's tokens were seen to stay in another session of the same process
        # for over 80 s on a loaded machine (Zenoh's routing of a peer that goes, not robomodel)
        close_session(session, before=lambda: undeclare_all(*tokens))


def _real_graph(domain: str) -> tuple[list[str], list[str]]:
    """6 nodes and 10 topics of an honest peer, beside the flood."""
    keys: list[str] = []
    for n in range(6):
        topics = [f"real_topic_{t}" for t in range(10) if t % 6 == n]
        node_keys = _token_keys(domain, "5eed", f"real_{n}", topics)
        keys += [k.replace("/5eed/0/", f"/5eed/{n}/", 1) for k in node_keys]
    return keys, [f"/real_topic_{t}" for t in range(10)]


def _flood(domain: str, count: int) -> list[str]:
    return _token_keys(domain, "f100d", "flood", [f"flood_{i}" for i in range(count)])


def _cli_env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS")}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), str(ROOT)])
    return env


def test_a_flood_of_tokens_hides_no_entity_of_another_peer() -> None:
    """2,000 tokens of one peer: ``topic list`` and ``node list`` still show every topic and
    node of the others, and the flood's (a liveliness query of that many tokens came back
    empty, and a listing printed before the flood's tokens arrived left them out)."""
    domain = unique_domain()
    real_keys, real_topics = _real_graph(domain)

    def listing(verb: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [*ROBOMODEL, verb, "list", "--domain-id", domain],
            capture_output=True,
            text=True,
            env=_cli_env(),
            timeout=scaled(60),
        )

    nodes = ["/flood", *(f"/real_{n}" for n in range(6))]
    seen: dict[str, list[str]] = {}

    def complete(verb: str, count: int, honest: list[str]) -> bool:
        run = listing(verb)
        assert run.returncode == 0, run.stderr
        seen[verb] = run.stdout.splitlines()
        assert set(honest) <= set(seen[verb])  # in every listing, complete or not
        return len(seen[verb]) == count

    with _peer(_flood(domain, 2000)), _peer(real_keys):
        # Every listing shows the honest peer's topics and nodes. A listing waits a bounded
        # time for the flood's 2,000 tokens to stop arriving (settled_graph); on a machine
        # loaded beyond that bound a listing may print before they are all in, so a later
        # listing in the same graph may be the complete one.
        wait_until(lambda: complete("topic", 10 + 2000, real_topics), 180,
                   what=lambda: f"a complete topic list ({len(seen['topic'])} of 2010 shown)",
                   interval_s=0.5)  # fmt: skip
        wait_until(
            lambda: complete("node", len(nodes), nodes[1:]),
            180,
            what=lambda: f"a complete node list: {seen['node']}",
            interval_s=0.5,
        )
    assert seen["node"] == nodes  # in order


def test_tokens_past_the_per_peer_bound_are_left_out_with_one_warning_and_exit_1(
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
    cli: Callable[..., ToolResult],
) -> None:
    from robomodel.runtime.transport import _zenoh_graph

    monkeypatch.setattr(_zenoh_graph, "MAX_TOKENS_PER_PEER", 300)
    domain = unique_domain()
    real_keys, real_topics = _real_graph(domain)
    with (
        _peer(_flood(domain, 500)),
        _peer(real_keys),
        caplog.at_level(logging.WARNING, logger="robomodel.runtime"),
    ):
        result = cli("topic", "list", "--domain-id", domain)
    listed = result.out.splitlines()
    assert result.code == 1
    assert set(real_topics) <= set(listed)  # the other peer loses nothing
    # 300 tokens of the flooding peer are kept: its node's and 299 publishers', or 300 of those
    assert len(listed) - 10 in (299, 300)
    bounded = [r for r in caplog.records if "more entities than robomodel keeps" in r.getMessage()]
    assert len(bounded) == 1 and "300 for peer f100d" in bounded[0].getMessage()
    assert "could not be read completely" in result.err


def test_the_graph_is_complete_again_when_the_flood_goes() -> None:
    """Bounds per peer and in all; the count of tokens left out follows their undeclaration."""
    from robomodel.runtime.transport._zenoh_common import close_session
    from robomodel.runtime.transport._zenoh_graph import GraphCache
    from robomodel.runtime.transport._zenoh_session import open_session

    domain = unique_domain()
    session = open_session().session
    cache = GraphCache(session, int(domain), max_tokens=400, max_per_peer=250)
    try:
        with _peer(_flood(domain, 399)):
            wait_until(
                lambda: len(cache) + cache.left_out == 400, 30, what="the flood", interval_s=0.02
            )
            assert (len(cache), cache.left_out) == (250, 150)
            assert not cache.graph().complete
            with _peer(_token_keys(domain, "ab12", "other", [f"o{i}" for i in range(199)])):
                wait_until(
                    lambda: len(cache) + cache.left_out == 600,
                    30,
                    what="the other peer",
                    interval_s=0.02,
                )
                assert (len(cache), cache.left_out) == (400, 200)  # 150 of the other's kept
            wait_until(
                lambda: len(cache) + cache.left_out == 400,
                30,
                what=lambda: f"the other peer to go: {len(cache)} kept, {cache.left_out} left out",
                interval_s=0.02,
            )
            assert (len(cache), cache.left_out) == (250, 150)
        wait_until(
            lambda: len(cache) + cache.left_out == 0,
            30,
            what=lambda: f"the flood to go: {len(cache)} kept, {cache.left_out} left out",
            interval_s=0.02,
        )
        assert cache.graph().complete
    finally:
        cache.close()
        close_session(session)


class _Sample:
    def __init__(self, key: str, kind: Any) -> None:
        self.key_expr = key
        self.kind = kind


class _OfflineSession:
    """Enough of a Zenoh session for a GraphCache fed samples by the test."""

    def liveliness(self) -> _OfflineSession:
        return self

    def declare_subscriber(self, key: str, handler: Any, history: bool) -> _OfflineSession:
        return self

    def undeclare(self) -> None:
        pass


def test_a_left_out_token_declared_again_after_room_is_made_is_not_counted_twice() -> None:
    """Tokens reach a session by more than one route, so a declaration may come twice; the
    second one of a token left out stays left out, even once a removal has made room."""
    import zenoh

    from robomodel.runtime.transport._zenoh_graph import GraphCache

    domain = unique_domain()
    keys = _token_keys(domain, "ab12", "other", ["a", "b", "c"])
    cache = GraphCache(_OfflineSession(), int(domain), max_tokens=3, max_per_peer=3)
    put, delete = zenoh.SampleKind.PUT, zenoh.SampleKind.DELETE
    feed = cache._on_sample
    for key in keys:
        feed(_Sample(key, put))
    assert (len(cache), cache.left_out) == (3, 1)
    feed(_Sample(keys[0], delete))  # room for one
    feed(_Sample(keys[3], put))  # the left-out one again, by another route
    assert (len(cache), cache.left_out) == (2, 1)
    for key in keys[1:]:
        feed(_Sample(key, delete))
    assert (len(cache), cache.left_out) == (0, 0)
    assert cache.graph().complete


def _rss_mib(pid: int) -> float:
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS")


FLOODER = textwrap.dedent(
    """
    import sys, zenoh
    conf = zenoh.Config()
    conf.insert_json5("mode", '"peer"')
    conf.insert_json5("connect/endpoints", '["%s"]')
    conf.insert_json5("scouting/multicast/enabled", "false")
    session = zenoh.open(conf)
    tokens = [session.liveliness().declare_token(f"@ros2_lv/9/f100d/0/{i}/MP/%%/%%/flood/%%t{i}/%s")
              for i in range(int(sys.argv[1]))]
    print("declared", flush=True)
    sys.stdin.readline()
    # undeclared before the session closes, as a node that ends does: the tokens of a peer
    # that vanished stayed in the router for over 100 s once on a loaded machine (Zenoh's
    # handling of a lost peer, not the trimming this test checks)
    for token in tokens:
        token.undeclare()
    session.close()
    """
)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc, trims glibc")
def test_the_router_gives_back_the_memory_of_tokens_that_went() -> None:
    """A router's memory grows with a peer's 8,000 tokens (Zenoh's routing tables) and goes
    back near where it was once they are gone (it kept 75 MiB of a flood before)."""
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    env = {**_cli_env(), "ZENOH_CONFIG_OVERRIDE": ""}
    router = subprocess.Popen(
        [*ROBOMODEL, "router", "--listen", endpoint],
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        start_new_session=True,
    )
    try:
        assert router.stderr is not None and "Started Zenoh router" in router.stderr.readline()
        baseline = _rss_mib(router.pid)
        flooder = subprocess.Popen(
            [sys.executable, "-c", FLOODER % (endpoint, STRING), "8000"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
        )
        assert flooder.stdout is not None and flooder.stdout.readline() == "declared\n"
        wait_until(
            lambda: _rss_mib(router.pid) > baseline + 10,
            30,
            what="the router to hold the tokens",
            interval_s=0.02,
        )
        peak = _rss_mib(router.pid)
        flooder.communicate("\n", timeout=scaled(60))
        # Half the growth back: the allocator returns freed pages when it trims, not at once
        # (a third was missed once in a quiet run); the leak this guards kept all of it.
        wait_until(
            lambda: _rss_mib(router.pid) < baseline + (peak - baseline) / 2,
            60,
            what=f"the router's memory to go back (baseline {baseline:.0f} MiB, peak {peak:.0f})",
            interval_s=0.02,
        )
    finally:
        router.terminate()
        router.wait(scaled(10))
