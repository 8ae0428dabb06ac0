"""posture: the Python client of postured (standard library only).

See :mod:`posture.client` and docs/protocol.md. ``posturectl`` (next to this package)
is the command-line client built on it.
"""
from .client import (DEFAULT_TIMEOUT, MAX_LINE, MAX_WORDS, Client, ConnectionClosed,
                     PostureError, ProtocolError, default_socket_path, format_command,
                     is_silent, quote_word, result_of, split_tag)

__all__ = [
    "Client", "PostureError", "ProtocolError", "ConnectionClosed", "default_socket_path",
    "format_command", "quote_word", "is_silent", "split_tag", "result_of",
    "DEFAULT_TIMEOUT", "MAX_LINE", "MAX_WORDS",
]
