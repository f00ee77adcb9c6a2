"""Reads an LCM log file (lcm-logger's format) without the LCM Python binding, which Debian 12 does not package.

    from gpilot_lcmlog import EventLog
    from gpilot import gesture_cmd_t
    for event in EventLog("log.lcmlog"):
        if event.channel == "GESTURE_CMD":
            print(event.timestamp, gesture_cmd_t.decode(event.data).mode)

Same names as lcm.EventLog's events (eventnum, timestamp in microseconds, channel, data), so code written
against it also runs with the binding. A signed bus appends a 56-byte trailer to each message; the generated
decode() reads its fields and ignores what follows.
"""
import struct

_SYNC = 0xEDA1DA01
_HEADER = struct.Struct(">IqqII")  # sync, event number, timestamp (us), channel length, data length


class Event(object):
    __slots__ = ["eventnum", "timestamp", "channel", "data"]

    def __init__(self, eventnum, timestamp, channel, data):
        self.eventnum, self.timestamp, self.channel, self.data = eventnum, timestamp, channel, data


class EventLog(object):
    """The events of a log file, in order. A truncated last event (a logger killed mid-write) ends the log."""

    def __init__(self, path):
        self.path = path

    def __iter__(self):
        with open(self.path, "rb") as f:
            while True:
                header = f.read(_HEADER.size)
                if len(header) < _HEADER.size:
                    return
                sync, eventnum, timestamp, channel_len, data_len = _HEADER.unpack(header)
                if sync != _SYNC:
                    raise ValueError("%s: not an LCM log (bad sync word at offset %d)" % (self.path, f.tell() - _HEADER.size))
                channel = f.read(channel_len)
                data = f.read(data_len)
                if len(channel) < channel_len or len(data) < data_len:
                    return
                yield Event(eventnum, timestamp, channel.decode("utf-8"), data)
