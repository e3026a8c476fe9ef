"""A transform buffer with the semantics of tf2's ``BufferCore`` (``tf2/src/buffer_core.cpp``).

Frames are numbered in order of first appearance (child before parent, as tf2), which fixes
the order of :meth:`BufferCore.all_frames_as_string` and :meth:`BufferCore.all_frames_as_yaml`.
Each child frame has one cache; a lookup walks from the source and the target up to their
common ancestor at one time. Time 0 means "the latest time common to the dynamic links on the
path" (static links never limit it). Times are integer nanoseconds, as tf2's ``TimePoint``.
"""

from __future__ import annotations

import math
import warnings

from robomodel.description.rigid import IDENTITY_POSE as IDENTITY
from robomodel.description.rigid import PoseXyzw as Pose
from robomodel.description.rigid import compose_poses as compose
from robomodel.description.rigid import invert_pose as inverse
from robomodel.errors import close_matches
from robomodel.tf.cache import StaticCache, Storage, TimeCache
from robomodel.tf.exceptions import (
    ConnectivityError,
    ExtrapolationError,
    InvalidArgumentError,
    LookupError,
    TransformError,
)
from robomodel.tf.message import TransformStamped, display_time

__all__ = ["DEFAULT_CACHE_TIME_NS", "BufferCore", "TFWarning"]

DEFAULT_CACHE_TIME_NS = 10_000_000_000  # tf2's BUFFER_CORE_DEFAULT_CACHE_TIME
_MAX_GRAPH_DEPTH = 1000
_QUATERNION_TOLERANCE = 10e-3


class TFWarning(UserWarning):
    """A transform was ignored (tf2 logs these: TF_SELF_TRANSFORM, TF_NAN_INPUT, ...)."""


def _strip(frame: str) -> str:
    return frame[1:] if frame.startswith("/") else frame


def _rejections(parent: str, child: str, values: tuple[float, ...], authority: str) -> list[str]:
    """tf2's reasons to ignore a transform (``BufferCore::setTransformImpl``), in its order
    and words; ``values`` is the translation then the rotation (xyzw)."""
    problems = []
    if child == parent:
        problems.append(
            f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with '
            f'frame_id and  child_frame_id "{child}" because they are the same'
        )
    if not child:
        problems.append(
            f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" because '
            "child_frame_id not set "
        )
    if not parent:
        problems.append(
            f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from '
            f'authority "{authority}" because frame_id not set'
        )
    # One addition flags a NaN among the seven (the exact test runs only then: inf - inf).
    if math.isnan(sum(values)) and any(math.isnan(v) for v in values):
        problems.append(
            f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority '
            f'"{authority}" because of a nan value in the transform'
        )
    x, y, z, w = values[3:]
    if not abs(x * x + y * y + z * z + w * w - 1.0) < _QUATERNION_TOLERANCE:
        problems.append(
            f'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "{child}" '
            f'from authority "{authority}" because of an invalid quaternion in the '
            f"transform ({x:f} {y:f} {z:f} {w:f})"
        )
    return problems


def _yaml_scalar(text: str, style: str | None) -> str:
    """``text`` as one YAML scalar on one line, written by PyYAML's emitter (``style``: None
    for plain where plain reads back the same, ``'`` single-quoted, ``"`` double-quoted)."""
    import yaml

    dumped = yaml.safe_dump(text, default_style=style, width=float("inf"), allow_unicode=True)
    return dumped.removesuffix("\n...\n").removesuffix("\n")


def _yaml_key(name: str) -> str:
    """A frame name as a mapping key: plain as tf2 writes it, quoted when plain would not
    read back as the name."""
    return _yaml_scalar(name, None if name.isprintable() else '"')


def _yaml_quoted(name: str) -> str:
    """A name single-quoted as tf2 writes it (``'base'``), double-quoted with escapes when it
    holds a line break or another character a single-quoted scalar cannot."""
    return _yaml_scalar(name, "'" if name.isprintable() else '"')


class BufferCore:
    """Stores transforms between frames over time and answers lookups between any two.

    Args:
        cache_time_ns: How long dynamic transforms are kept behind the newest one [ns].
    """

    def __init__(self, cache_time_ns: int = DEFAULT_CACHE_TIME_NS) -> None:
        self.cache_time_ns = cache_time_ns
        self._frames: list[str] = []  # in order of first appearance
        self._known: set[str] = set()  # the same frames: O(1) membership for every lookup
        self._caches: dict[str, TimeCache | StaticCache] = {}
        self._authority: dict[str, str] = {}

    # -- inserting -------------------------------------------------------------------------
    def _ignore(self, what: str) -> bool:
        warnings.warn(what, TFWarning, stacklevel=3)
        return False

    def _number(self, frame: str) -> None:
        if frame not in self._known:
            self._known.add(frame)
            self._frames.append(frame)

    def set_transform(
        self, transform: TransformStamped, authority: str, is_static: bool = False
    ) -> bool:
        """Add a transform; False (and a :class:`TFWarning` with tf2's text) if rejected."""
        parent = transform.frame_id
        if parent[:1] == "/":
            parent = parent[1:]
        child = transform.child_frame_id
        if child[:1] == "/":
            child = child[1:]
        values = (*transform.translation_m, *transform.rotation_xyzw)
        x, y, z, w = transform.rotation_xyzw
        # The cheap tests in one condition: this is the hot path, and the messages are built
        # (and the tests made exactly) only for a transform that may be rejected.
        if (
            child == parent
            or not child
            or not parent
            or math.isnan(sum(values))
            or not abs(x * x + y * y + z * z + w * w - 1.0) < _QUATERNION_TOLERANCE
        ):
            problems = _rejections(parent, child, values, authority)
            if problems:
                return self._ignore("\n".join(problems))
        known = self._known
        if child not in known:
            self._number(child)
        cache = self._caches.get(child)
        if cache is None or cache.is_static != is_static:
            cache = StaticCache() if is_static else TimeCache(self.cache_time_ns)
            self._caches[child] = cache
        if parent not in known:
            self._number(parent)
        sample = Storage(
            transform.stamp_ns,
            parent,
            (float(values[0]), float(values[1]), float(values[2])),
            (float(x), float(y), float(z), float(w)),
        )
        if not cache.insert(sample):
            return self._ignore(
                f"TF_OLD_DATA ignoring data from the past for frame {child} at time "
                f"{display_time(transform.stamp_ns)} according to authority {authority}\n"
                "Possible reasons are listed at http://wiki.ros.org/tf/Errors%20explained"
            )
        self._authority[child] = authority
        return True

    def clear(self) -> None:
        """Forget dynamic data (static transforms stay, as in tf2)."""
        for cache in self._caches.values():
            cache.clear()

    # -- looking up ------------------------------------------------------------------------
    def _validate(self, frame: str, argument: str) -> None:
        if not frame:
            raise InvalidArgumentError(
                f'Invalid argument "{frame}" passed to {argument} - in tf2 frame_ids cannot be '
                "empty"
            )
        if frame.startswith("/"):
            raise InvalidArgumentError(
                f'Invalid argument "{frame}" passed to {argument} - in tf2 frame_ids cannot '
                "start with a '/'"
            )
        if frame not in self._known:
            hint = close_matches(frame, self._frames)
            suggestion = f"Did you mean {', '.join(repr(h) for h in hint)}?" if hint else ""
            raise LookupError(f'"{frame}" passed to {argument} does not exist. {suggestion}')

    def latest_parent(self, frame: str) -> tuple[int | None, str | None]:
        """The parent of ``frame`` in its newest transform and that transform's stamp [ns]
        (None for a static transform, which never ages); ``(None, None)`` for a root or an
        unknown frame. RViz's TF display draws arrows to parents and ages frames by it."""
        cache = self._caches.get(frame)
        if cache is None:
            return None, None
        stamp, parent = cache.latest()
        return (None if cache.is_static else stamp), parent

    def _parent(self, frame: str) -> tuple[int, str | None]:
        cache = self._caches.get(frame)
        return (0, None) if cache is None else cache.latest()

    def _connectivity(self, target: str, source: str) -> ConnectivityError:
        return ConnectivityError(
            f"Could not find a connection between '{target}' and '{source}' because they are "
            "not part of the same tree.Tf has two or more unconnected trees."
        )

    def _loop(self) -> LookupError:
        return LookupError(
            "The tf tree is invalid because it contains a loop.\n"
            + self.all_frames_as_string()
            + "\n"
        )

    def latest_common_time_ns(self, target: str, source: str) -> int:
        """tf2's ``getLatestCommonTime``: min newest stamp of the dynamic links on the path."""
        if source == target:
            cache = self._caches.get(source)
            return 0 if cache is None else cache.latest_ns
        chain: list[tuple[int, str]] = []
        frame: str | None = source
        common = math.inf
        depth = 0
        while frame is not None:
            stamp, parent = self._parent(frame)
            if parent is None:
                break
            if stamp != 0:
                common = min(common, stamp)
            chain.append((stamp, parent))
            frame = parent
            if frame == target:
                return 0 if common == math.inf else int(common)
            depth += 1
            if depth > _MAX_GRAPH_DEPTH:
                raise self._loop()
        frame = target
        common = math.inf
        common_parent = None
        depth = 0
        while True:
            stamp, parent = self._parent(frame)
            if parent is None:
                break
            if stamp != 0:
                common = min(common, stamp)
            if any(p == parent for _, p in chain):
                common_parent = parent
                break
            frame = parent
            if frame == source:
                return 0 if common == math.inf else int(common)
            depth += 1
            if depth > _MAX_GRAPH_DEPTH:
                raise self._loop()
        if common_parent is None:
            raise self._connectivity(target, source)
        for stamp, parent in chain:
            if stamp != 0:
                common = min(common, stamp)
            if parent == common_parent:
                break
        return 0 if common == math.inf else int(common)

    def _walk(self, target: str, source: str, time_ns: int) -> tuple[Pose, int]:
        """``(pose of source in target, time)`` following tf2's ``walkToTopParent``.

        Poses are accumulated as (translation, quaternion) exactly as tf2's
        ``TransformAccum`` does, so pure rotations about one axis stay exact.
        """
        if time_ns == 0:
            time_ns = self.latest_common_time_ns(target, source)
        source_to_top = IDENTITY
        frame = source
        top = frame
        extrapolation: ExtrapolationError | None = None
        depth = 0
        while True:
            cache = self._caches.get(frame)
            if cache is None:
                top = frame
                break
            try:
                sample = cache.get(time_ns)
            except ExtrapolationError as exc:
                top, extrapolation = frame, exc
                break
            if frame == target:
                return source_to_top, time_ns
            source_to_top = compose((sample.translation, sample.rotation_xyzw), source_to_top)
            top = frame
            frame = sample.parent
            depth += 1
            if depth > _MAX_GRAPH_DEPTH:
                raise self._loop()
        target_to_top = IDENTITY
        frame = target
        depth = 0
        while frame != top:
            cache = self._caches.get(frame)
            if cache is None:
                break
            try:
                sample = cache.get(time_ns)
            except ExtrapolationError as exc:
                raise type(exc)(
                    f"{exc}, when looking up transform from frame [{source}] to frame [{target}]"
                ) from None
            if frame == source:
                return inverse(target_to_top), time_ns
            target_to_top = compose((sample.translation, sample.rotation_xyzw), target_to_top)
            frame = sample.parent
            depth += 1
            if depth > _MAX_GRAPH_DEPTH:
                raise self._loop()
        if frame != top:
            if extrapolation is not None:
                raise type(extrapolation)(
                    f"{extrapolation}, when looking up transform from frame [{source}] to "
                    f"frame [{target}]"
                )
            raise self._connectivity(target, source)
        return compose(inverse(target_to_top), source_to_top), time_ns

    def lookup_transform(self, target: str, source: str, time_ns: int = 0) -> TransformStamped:
        """The pose of ``source`` in ``target`` (maps data from source into target).

        Args:
            target: Target frame (the result's ``frame_id``).
            source: Source frame (the result's ``child_frame_id``).
            time_ns: Time [ns]; 0 means the latest time common to the path.

        Raises:
            LookupError, ConnectivityError, ExtrapolationError, InvalidArgumentError: with
                tf2's messages.
        """
        if target == source:
            stamp = time_ns
            if time_ns == 0:
                cache = self._caches.get(target)
                stamp = 0 if cache is None else cache.latest_ns
            return TransformStamped(target, source, stamp_ns=stamp)
        self._validate(target, "lookupTransform argument target_frame")
        self._validate(source, "lookupTransform argument source_frame")
        if time_ns == 0:
            # One hop (target is source's parent) at the latest time: the newest sample is the
            # answer, as the walk below would find it (what a viewer asks once per joint).
            cache = self._caches.get(source)
            if cache is not None:
                latest_ns, parent = cache.latest()
                if parent == target:
                    sample = cache.get(latest_ns)
                    return TransformStamped(
                        target, source, sample.translation, sample.rotation_xyzw, sample.stamp_ns
                    )
        (t, q), stamp = self._walk(target, source, time_ns)
        return TransformStamped(target, source, t, q, stamp)

    def can_transform(self, target: str, source: str, time_ns: int = 0) -> bool:
        """Whether :meth:`lookup_transform` would succeed (never raises for missing frames)."""
        if target == source:
            return True
        try:
            self.lookup_transform(target, source, time_ns)
        except TransformError:
            return False
        return True

    # -- introspection ---------------------------------------------------------------------
    @property
    def frames(self) -> tuple[str, ...]:
        """Every frame seen, in order of first appearance."""
        return tuple(self._frames)

    def all_frames_as_string(self) -> str:
        """``Frame X exists with parent Y.`` per child frame (tf2's ``allFramesAsString``)."""
        lines = []
        for frame in self._frames:
            cache = self._caches.get(frame)
            if cache is None:
                continue
            _, parent = cache.latest()
            lines.append(f"Frame {frame} exists with parent {parent or 'NO_PARENT'}.\n")
        return "".join(lines)

    def all_frames_as_yaml(self, current_time_ns: int = 0) -> str:
        """tf2's ``allFramesAsYAML`` (what view_frames reads). Frame and broadcaster names come
        from peers: each is written by PyYAML's emitter (:func:`_yaml_key`,
        :func:`_yaml_quoted`), so ``it's: [x`` or a line break reads back as the name."""
        out = []
        if not self._frames:
            out.append("[]")
        for frame in self._frames:
            cache = self._caches.get(frame)
            if cache is None:
                continue
            _, parent = cache.latest()
            if parent is None:
                continue
            span = cache.latest_ns - cache.oldest_ns
            rate = len(cache) * 1e9 / max(span, 100_000)
            authority = self._authority.get(frame, "no recorded authority")
            out.append(f"{_yaml_key(frame)}: \n")
            out.append(f"  parent: {_yaml_quoted(parent)}\n")
            out.append(f"  broadcaster: {_yaml_quoted(authority)}\n")
            out.append(f"  rate: {rate:.3f}\n")
            out.append(f"  most_recent_transform: {display_time(cache.latest_ns)}\n")
            out.append(f"  oldest_transform: {display_time(cache.oldest_ns)}\n")
            if current_time_ns != 0:
                out.append(f"  transform_delay: {(current_time_ns - cache.latest_ns) / 1e9:.3f}\n")
            out.append(f"  buffer_length: {span / 1e9:.3f}\n")
        return "".join(out)

    def as_yaml(self, current_time_ns: int = 0) -> str:
        """Alias of :meth:`all_frames_as_yaml`."""
        return self.all_frames_as_yaml(current_time_ns)
