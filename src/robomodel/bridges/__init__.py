"""WebSocket bridges to the bus, as ROS users reach their robots from outside ROS.

:mod:`.rosbridge` speaks rosbridge's v2 JSON protocol (``rosbridge_server``'s
``rosbridge_websocket``, port 9090) to roslibjs, roslibpy and browser dashboards, with the rosapi
services they call (:mod:`.rosapi`). Messages travel as rosbridge's JSON (:mod:`.json_mapping`);
every client's outgoing messages wait in a bounded queue (:mod:`.outbox`), so a slow client
loses messages, never the bridge its memory. The bounds are in :mod:`.limits`.

The WebSocket library (``websockets``) is the ``bridges`` extra; it is imported only when a
bridge starts.
"""

from robomodel.bridges.exceptions import BridgeError
from robomodel.bridges.limits import BridgeLimits

__all__ = ["BridgeError", "BridgeLimits"]
