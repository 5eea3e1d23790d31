"""The base color images of a glTF 2.0 file's materials, as arrays.

sr_load_scene reads the file (and checks it); its textures live in the
library, without their pixels, so the images the materials' base color
textures name are read again here from the file's JSON: an image's bytes
come from a data: URI, a file next to the model, or a buffer view (GLB's
binary chunk or a buffer's URI), and are decoded by sr_decode_image.
"""

from __future__ import annotations

import base64
import json
import os
import struct
import urllib.parse
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
from numpy.typing import NDArray

from . import _softrast

_GLB_MAGIC = b"glTF"
_GLB_JSON, _GLB_BIN = 0x4E4F534A, 0x004E4942


class _Document:
    def __init__(self, path: Union[str, bytes]) -> None:
        with open(path, "rb") as f:
            data = f.read()
        self.dir = os.path.dirname(os.path.abspath(os.fsdecode(path)))
        self.bin: Optional[bytes] = None
        if data[:4] == _GLB_MAGIC:
            offset = 12
            chunks: Dict[int, bytes] = {}
            while offset + 8 <= len(data):
                length, kind = struct.unpack_from("<II", data, offset)
                chunks.setdefault(kind, data[offset + 8:offset + 8 + length])
                offset += 8 + length + (-length % 4)
            data, self.bin = chunks.get(_GLB_JSON, b"{}"), chunks.get(_GLB_BIN)
        self.json = json.loads(data.decode("utf-8"))
        self.buffers: Dict[int, Optional[bytes]] = {}

    def _uri(self, uri: str) -> bytes:
        if uri.startswith("data:"):
            head, _, payload = uri.partition(",")
            return base64.b64decode(payload) if head.endswith(";base64") else \
                urllib.parse.unquote_to_bytes(payload)
        name = urllib.parse.unquote(uri)
        if os.path.isabs(name) or urllib.parse.urlparse(uri).scheme:
            raise ValueError(f"{uri}: only relative paths and data: URIs are read")
        with open(os.path.join(self.dir, name), "rb") as f:
            return f.read()

    def _buffer(self, index: int) -> Optional[bytes]:
        if index not in self.buffers:
            buf = self.json["buffers"][index]
            self.buffers[index] = self._uri(buf["uri"]) if "uri" in buf else self.bin
        return self.buffers[index]

    def image(self, index: int) -> bytes:
        img = self.json["images"][index]
        if "uri" in img:
            return self._uri(img["uri"])
        view = self.json["bufferViews"][img["bufferView"]]
        start = view.get("byteOffset", 0)
        data = self._buffer(view["buffer"])
        if data is None:
            raise ValueError(f"/images/{index}: its buffer has no data (no GLB binary chunk)")
        return data[start:start + view["byteLength"]]

    def base_color_image(self, material: int) -> Optional[NDArray[np.uint8]]:
        """The decoded base color image of material `material`, or None."""
        materials = self.json.get("materials", [])
        if material >= len(materials):
            return None
        # KHR_materials_pbrSpecularGlossiness's diffuse texture is drawn
        # in place of the base color's, as sr_load_scene reads it.
        sg = materials[material].get("extensions", {}).get("KHR_materials_pbrSpecularGlossiness")
        info = sg.get("diffuseTexture") if isinstance(sg, dict) else \
            materials[material].get("pbrMetallicRoughness", {}).get("baseColorTexture")
        if info is None:
            return None
        source = self.json["textures"][info["index"]].get("source")
        if source is None:
            return None
        return _softrast.decode_image(self.image(source), f"/images/{source}")


def base_color_images(path: Union[str, bytes],
                      materials: Sequence[Dict[str, Any]], lost: List[str]
                      ) -> Dict[int, Optional[NDArray[np.uint8]]]:
    """{material index: (H, W, 4) uint8 image} for the materials of
    `materials` (sr_load_scene's factors) that have a base color texture;
    an image that cannot be read is left out, with a line in `lost` for
    the caller's warning."""
    wanted = [i for i, m in enumerate(materials) if m["base_color_texture"] is not None]
    if not wanted:
        return {}
    try:
        doc = _Document(path)
    except (OSError, ValueError) as e:
        lost.append(f"softrast.load: {os.fsdecode(path)}: base color textures not kept: {e}")
        return {}
    images: Dict[int, Optional[NDArray[np.uint8]]] = {}
    for i in wanted:
        try:
            images[i] = doc.base_color_image(i)
        except (OSError, ValueError, KeyError, IndexError, TypeError) as e:
            lost.append(f"softrast.load: {os.fsdecode(path)}: /materials/{i}: base color "
                        f"texture not kept: {e}")
    return images
