"""ROS 1 on the wire: a master (XML-RPC), every node's slave API, TCPROS, ROS 1 messages."""
