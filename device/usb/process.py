"""The USB stream in a process of its own, so nothing the host's other threads do delays it.

Writing a block and reading a report are short, but each needs the interpreter lock; in one
process with the editor (its GUI thread painting, its render worker mixing) the streaming thread
waits for the lock at every transfer and the knob's 30 ms queue runs dry. Here a child process
owns the link and the stream (device.usb.streamer); the host hands it coefficient blocks through
a pipe, as far ahead of their play as `ahead` (the stream's lead), and gets back telemetry as
the device reports it. A host stalled for less than that lead is absorbed by the blocks already
handed over; the child's writes to the device stay on time meanwhile.

Messages, host to child: ("play", mask, limit, lead, block, watchdog_ms, hand, monitor),
("blocks", [CoefficientBlock, ...]), ("end",), ("close",). Child to host: ("info", InfoPayload) or
("error", exception) once opened; while playing ("monitor", LiveTelemetry), ("progress",
seconds, total), then ("done", Telemetry, underruns) or ("error", exception).
"""

from __future__ import annotations

import multiprocessing
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import suppress
from dataclasses import replace
from multiprocessing.connection import Connection
from typing import Any

from device.usb import protocol as p
from device.usb.errors import UsbDeviceError
from timeline.errors import HapticTimelineError
from timeline.plugins.device_protocol import (
    CoefficientBlock,
    Hand,
    LiveTelemetry,
    Monitor,
    Progress,
    Telemetry,
)
from timeline.plugins.device_protocol.child_process import end_child, prefer_real_time

START_SECONDS = 60.0  # a child that has not opened the device by then is not coming


class StreamProcess:
    """The host's end: a child process that opened the device and streams to it on request.

    `opener` is called in the child and returns (link, backend): a picklable module-level
    function with its arguments.
    """

    def __init__(self, opener: Callable[..., Any], args: tuple) -> None:
        context = multiprocessing.get_context("spawn")  # no fork of a process running Qt threads
        child_in, self._to_child = context.Pipe(duplex=False)
        self._from_child, child_out = context.Pipe(duplex=False)
        self.process = context.Process(
            target=serve, args=(child_in, child_out, opener, args), daemon=True, name="usb stream"
        )
        self.process.start()
        child_in.close()  # the child's ends: closed here, so its exit reads as the end of file
        child_out.close()
        self._lock = threading.Lock()  # one play at a time
        self.info: p.InfoPayload = self._message("opening the device", START_SECONDS)[1]

    def _message(self, what: str, timeout: float | None = None) -> tuple:
        """The child's next message; its error raised here, as one sentence."""
        if timeout is not None and not self._from_child.poll(timeout):
            self.close()
            raise UsbDeviceError(f"the USB stream process did not answer while {what}")
        try:
            message = self._from_child.recv()
        except (EOFError, OSError):
            raise self._gone(what) from None
        if message[0] == "error":
            raise message[1]
        return message

    def _gone(self, what: str) -> UsbDeviceError:
        """The sentence for a child that is not there any more."""
        self.process.join(timeout=1.0)
        return UsbDeviceError(
            f"the USB stream process ended unexpectedly (exit code {self.process.exitcode}) "
            f"while {what}, so playback stopped"
        )

    def play(
        self,
        blocks: Iterable[CoefficientBlock],
        settings: tuple,
        total: float | None,
        progress: Progress | None,
        monitor: Monitor | None,
    ) -> tuple[Telemetry, set[str], int]:
        """Stream `blocks` (handed over as the iterable yields them) with the settings (mask,
        torque limit, lead, block, watchdog ms, hand); the telemetry, the layers the device does
        not render, and the samples it played from an empty queue, as its last report said."""
        with self._lock:
            try:
                self._to_child.send(("play", *settings, monitor is not None))
            except OSError:
                raise self._gone("streaming") from None
            done, failed = threading.Event(), []
            feeder = threading.Thread(
                target=self._feed, args=(blocks, done, failed), daemon=True,
                name="usb stream feeder",
            )  # fmt: skip
            feeder.start()
            try:
                while True:
                    kind, *payload = self._message("streaming")
                    if kind == "monitor" and monitor:
                        monitor(payload[0])
                    elif kind == "progress" and progress:
                        progress(payload[0], total)
                    elif kind == "done":
                        break
            finally:
                done.set()
                feeder.join()
                if failed:  # the blocks' source failed (a render): that is what went wrong
                    raise failed[0]
            return payload[0], payload[1], payload[2]

    def _feed(
        self, blocks: Iterable[CoefficientBlock], done: threading.Event, failed: list
    ) -> None:
        """Hand the blocks over until the play ends (a list at once, else each as it comes),
        then the end of the stream; what the blocks' source raised goes into `failed`."""
        try:
            if isinstance(blocks, list):
                self._to_child.send(("blocks", blocks))
            else:
                for block in blocks:
                    if done.is_set():
                        break
                    self._to_child.send(("blocks", [block]))
        except OSError:
            pass  # the child is gone: the play's receiving end says so
        except BaseException as exc:  # noqa: BLE001 - raised again on the playing thread
            failed.append(exc)
        finally:
            with suppress(OSError, ValueError):
                self._to_child.send(("end",))

    def close(self) -> None:
        """Ask the child to stop the device and go; make sure it went."""
        end_child(self.process, self._to_child, self._from_child)


def serve(inbox: Connection, outbox: Connection, opener: Callable[..., Any], args: tuple) -> None:
    """The child: open the device, answer its info, then play each stream the host sends."""
    try:
        link, backend = opener(*args)
        if hasattr(backend, "warm_up"):
            backend.warm_up()
    except HapticTimelineError as exc:
        outbox.send(("error", exc))
        return
    outbox.send(("info", link.info))
    try:
        while True:
            message = inbox.recv()
            if message[0] == "play":
                _play(link, backend, inbox, outbox, *message[1:])
            elif message[0] == "close":
                break
    except (EOFError, OSError):
        pass  # the host went away: the device's watchdog ramps it down, STOP does it sooner
    finally:
        link.abort()
        link.close()


def _play(
    link: Any,
    backend: Any,
    inbox: Connection,
    outbox: Connection,
    mask: int,
    limit: float,
    lead: float,
    block: float,
    watchdog_ms: int,
    hand: Hand | None,
    monitored: bool,
) -> None:
    from device.usb.streamer import Chunker, Stream

    prefer_real_time()  # this process's thread writes every transfer: ahead of other programs
    blocks = _received(inbox)
    try:
        if hand is not None and hasattr(backend, "set_hand"):
            backend.set_hand(hand)
        stream = Stream(link, mask, limit, lead, block, start_block_s=lead / 2)
        chunker = Chunker(blocks, p.channel_names(mask))
        link.set_limits(float(stream.limits[0]), watchdog_ms)

        def progress(played: float, total: float | None) -> None:
            outbox.send(("progress", float(played)))

        def monitor(part: LiveTelemetry) -> None:
            outbox.send(("monitor", part))

        try:
            stream.run(chunker, progress, None, monitor if monitored else None)
            link.stop()
        except BaseException:
            link.abort()
            raise
        # A monitored play is the editor's, which judges the design itself (its findings) and
        # reads only the parts: judging the whole play here held its end (and so the next
        # play's start) for about 0.3 s per second played.
        tel = stream.telemetry(judged=not monitored)
        if getattr(backend, "realtime", True):  # an emulated device may not be
            tel = replace(tel, lateness=stream.lateness.counts())
        outbox.send(("done", tel, chunker.dropped, stream.underruns))
    except HapticTimelineError as exc:
        outbox.send(("error", exc))
    except Exception as exc:  # noqa: BLE001 - a bug in the child must still end the play
        outbox.send(("error", UsbDeviceError(f"the USB stream process failed ({exc!r})")))
    for _ in blocks:  # the host's feeder may still be handing blocks over: take them to the end
        pass


def _received(inbox: Connection) -> Iterator[CoefficientBlock]:
    """The blocks the host hands over, up to its end of the stream."""
    while True:
        message = inbox.recv()
        if message[0] != "blocks":
            return
        yield from message[1]
