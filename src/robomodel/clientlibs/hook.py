"""Installs the client-library import finder: ``robomodel-clientlibs.pth`` imports this at
interpreter start (so it imports nothing heavy), unless ``ROBOMODEL_CLIENTLIBS=0``."""

from __future__ import annotations

from robomodel.clientlibs.finder import install

install()
