"""One line for a request that a handler could not serve, the traceback only at DEBUG level.

A request from a peer can make any handler fail (a JSON argument nested 100,000 deep raises
RecursionError); the serving process then logs one line naming the service and the error and
answers the caller with it, instead of printing a traceback for every bad request.
"""

from __future__ import annotations

import logging
import sys

__all__ = ["log_failure"]


def log_failure(log: logging.Logger, what: str, *args: object) -> None:
    """Log the exception being handled as one warning line: ``what % args: Type: message``."""
    exc = sys.exc_info()[1]
    detail = f"{type(exc).__name__}: {str(exc)[:500]}" if exc is not None else "unknown error"
    log.warning(what + ": %s", *args, detail)
    log.debug("traceback of the failure above", exc_info=True)
