"""A file upload that checks sizes before it reads: :class:`FileUpload`.

Panel's ``FileInput`` reads every chosen file in the browser and sends it whole, in one websocket message; a file
over the server's message limit closes the session's connection with nothing said. Here the browser compares each
file's size (known before reading) with the limit and sends only its name and size when it is over; a file
within it is sent on its own message. The server checks the name and the size again
(:func:`dashboard.uploads.checked_name`, :func:`~dashboard.uploads.checked_size`): a browser is not trusted.
"""

from __future__ import annotations

import base64
import binascii
from collections.abc import Callable

import param
from panel.custom import JSComponent

from dashboard.uploads import UploadRefused, checked_name, checked_size, size_text

__all__ = ["FileUpload"]


class FileUpload(JSComponent):
    """An ``<input type=file>`` whose files reach ``on_files({name: bytes})`` once all have come, or whose refusal
    reaches ``on_refused(message)``; nothing of a file over ``max_bytes`` is read."""

    accept = param.String("", doc="File suffixes offered by the browser's dialog ('.AT2,.csv').")
    multiple = param.Boolean(False, doc="Whether several files may be chosen at once.")
    max_bytes = param.Integer(1_000_000, bounds=(1, None), doc="Largest file [bytes].")
    max_files = param.Integer(1, bounds=(1, None), doc="Most files at once.")

    _esm = """
    export function render({ model, el }) {
      const input = document.createElement("input");
      input.type = "file";
      input.className = "pounding-upload";
      const sync = () => { input.accept = model.accept; input.multiple = model.multiple; };
      sync();
      model.on(["accept", "multiple"], sync);
      input.addEventListener("change", () => {
        const files = Array.from(input.files);
        const batch = Date.now() + Math.random();
        const over = files.filter((f) => f.size > model.max_bytes);
        if (files.length > model.max_files || over.length > 0) {
          // refused on sizes alone: nothing of the files is read
          model.send_msg({ batch, refused: files.map((f) => ({ name: f.name, size: f.size })) });
          input.value = "";
          return;
        }
        files.forEach((file, index) => {
          const reader = new FileReader();
          reader.onload = () => {
            const url = String(reader.result);
            model.send_msg({ batch, index, total: files.length, name: file.name, size: file.size,
                             data: url.slice(url.indexOf(",") + 1) });
          };
          reader.readAsDataURL(file);
        });
        input.value = "";
      });
      el.appendChild(input);
    }
    """

    def __init__(self, on_files: Callable[[dict[str, bytes]], None], on_refused: Callable[[str], None], **params):
        super().__init__(**params)
        self._on_files = on_files
        self._on_refused = on_refused
        self._pending: dict = {}  # batch -> {index: (name, bytes)}

    def receive(self, data) -> None:
        """Take one message of the browser (also what a test sends): a refusal on sizes, or one file of a batch."""
        try:
            files = self._take(data)
        except UploadRefused as refused:
            self._pending.clear()
            self._on_refused(refused.message)
            return
        if files is not None:
            self._on_files(files)

    def _take(self, data) -> dict[str, bytes] | None:
        if not isinstance(data, dict):
            raise UploadRefused("The upload did not arrive whole: choose the files again.")
        if "refused" in data:
            chosen = data["refused"] if isinstance(data["refused"], list) else []
            if len(chosen) > self.max_files:
                raise UploadRefused(f"{len(chosen)} files chosen, more than the {self.max_files} an upload may hold: "
                                    "choose fewer.")
            for entry in chosen:
                checked_size(str(entry.get("name", "")), int(entry.get("size", 0)), self.max_bytes)
            raise UploadRefused("The upload did not arrive whole: choose the files again.")
        name = checked_name(str(data.get("name", "")))
        try:
            total, index = int(data["total"]), int(data["index"])
            content = base64.b64decode(str(data["data"]), validate=True)
        except (KeyError, TypeError, ValueError, binascii.Error):
            raise UploadRefused(f"{name} did not arrive whole: choose it again.") from None
        checked_size(name, len(content), self.max_bytes)
        if not 1 <= total <= self.max_files or not 0 <= index < total:
            raise UploadRefused(f"At most {self.max_files} files at once, each up to {size_text(self.max_bytes)}: choose fewer.")
        key = str(data.get("batch"))
        if key not in self._pending and len(self._pending) >= 4:  # batches left unfinished: only the newest is awaited
            self._pending.clear()
        batch = self._pending.setdefault(key, {})
        batch[index] = (name, content)
        if len(batch) < total:
            return None
        del self._pending[key]
        return {name: content for name, content in (batch[i] for i in sorted(batch))}

    def _handle_msg(self, data) -> None:
        self.receive(data)
