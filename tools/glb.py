"""glb.py - the binary glTF the generators in tools/ write: a buffer of
typed arrays, each with its bufferView and accessor, and the file of the
JSON and that buffer (glTF 2.0, "GLB File Format Specification")."""
import json
import struct


class Buffer:
    """The one buffer's arrays, each 4-byte aligned."""

    def __init__(self):
        self.chunks, self.views, self.accessors = [], [], []

    def add(self, fmt, values, fields):
        """An array of struct format `fmt` (f, H, ...): its accessor's index."""
        raw = struct.pack("<%d%s" % (len(values), fmt), *values)
        at = sum(len(c) for c in self.chunks)
        self.chunks.append(raw + b"\0" * (-len(raw) % 4))
        self.views.append({"buffer": 0, "byteOffset": at, "byteLength": len(raw)})
        self.accessors.append(dict(bufferView=len(self.views) - 1, **fields))
        return len(self.accessors) - 1

    def bytes(self):
        return b"".join(self.chunks)


def write(path, doc, buf):
    """doc (without accessors, bufferViews, buffers) and buf as a .glb."""
    blob = buf.bytes()
    write_chunks(path, dict(doc, accessors=buf.accessors, bufferViews=buf.views,
                            buffers=[{"byteLength": len(blob)}]), blob)


def write_chunks(path, doc, blob):
    """A complete doc and its buffer's bytes as a .glb: the JSON chunk
    padded with spaces, the BIN chunk already 4-byte aligned."""
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\0") + bytes(blob))
