"""Shared fixtures: the corpus of ROS 2 launch files and a package index over it."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex

CORPUS = Path(__file__).resolve().parent / "corpus"


@pytest.fixture
def corpus_index() -> PackageIndex:
    """Packages of the corpus only (no environment), so test fixtures win over shipped ones."""
    return PackageIndex(package_paths=[CORPUS], use_environment=False)
