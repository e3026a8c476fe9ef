"""Transports that carry topics, graph information and parameter calls between nodes."""
