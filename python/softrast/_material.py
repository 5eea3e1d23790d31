"""Materials of loaded scenes: glTF's metallic-roughness factors and base color texture."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence, Union

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from .typing import AlphaMode, Image


class Material:
    """A glTF 2.0 metallic-roughness material as :func:`softrast.load` reads it
    (the defaults are glTF's).

    base_color: (4,) float32 linear RGBA factor.
    base_color_texture: (H, W, 4) uint8 sRGB image, row 0 at the top, or None.
    texcoord: the texture coordinate set the texture reads (0 or 1).
    metallic, roughness: factors in [0, 1].
    emissive: (3,) float32 linear RGB (times ``emissive_strength``).
    alpha_mode: "opaque", "mask" or "blend"; alpha_cutoff for "mask".
    double_sided, unlit: the material's flags (KHR_materials_unlit).
    ior: the index of refraction, >= 1 (KHR_materials_ior; 1.5: F0 0.04),
    which transmission also refracts by.
    specular, specular_color: the dielectric's reflection strength in [0, 1]
    and F0 tint (3,) >= 0 (KHR_materials_specular).
    clearcoat, clearcoat_roughness: a clear coat's weight and roughness in
    [0, 1] (KHR_materials_clearcoat; 0: none).
    sheen_color, sheen_roughness: (3,) in [0, 1] and [0, 1]
    (KHR_materials_sheen; black: none).
    transmission: the share of light let through, in [0, 1]
    (KHR_materials_transmission; 0: opaque).
    thickness: the volume's thickness in object units (KHR_materials_volume;
    0: thin-walled); attenuation_color: (3,) float32 linear RGB that white
    light keeps after attenuation_distance (world units; 0: no absorption).
    anisotropy_strength, anisotropy_rotation: how far the highlight stretches,
    in [0, 1], along the tangent turned by the rotation (radians,
    counter-clockwise) (KHR_materials_anisotropy; 0: isotropic).
    iridescence: a thin film's weight in [0, 1] (KHR_materials_iridescence;
    0: none), its iridescence_ior >= 1 and its thickness in nm,
    iridescence_thickness_max, or from iridescence_thickness_min to it
    across a loaded file's thickness texture.

    ``render`` draws the base color of a loaded instance (factor times
    texture times vertex color, drawn into its Mesh by :func:`load`) into
    ``color`` and ``rgba``.  With ``shading="pbr"`` it draws the whole
    material as softrast render does: every factor and flag (a material
    that is not double-sided has its back faces culled; "mask" cuts out
    where alpha < alpha_cutoff, "blend" is blended, farthest first, after
    the rest) and, for an instance :func:`load` made, every texture of the
    file (base color, metallic-roughness, normal, occlusion, emissive).
    For an instance of your own Mesh the base color is ``base_color``
    times the Mesh's colors and texture.  A transmissive material
    (``transmission`` > 0) shows the opaque instances behind it, refracted,
    blurred by its roughness and tinted (docs/pbr.md); the file's
    transmission and thickness textures are drawn for a loaded instance.
    """

    __slots__ = ("base_color", "base_color_texture", "texcoord", "metallic", "roughness",
                 "emissive", "emissive_strength", "alpha_mode", "alpha_cutoff", "double_sided",
                 "unlit", "normal_scale", "occlusion_strength", "ior", "specular",
                 "specular_color", "clearcoat", "clearcoat_roughness", "sheen_color",
                 "sheen_roughness", "transmission", "thickness", "attenuation_color",
                 "attenuation_distance", "anisotropy_strength", "anisotropy_rotation",
                 "iridescence", "iridescence_ior", "iridescence_thickness_min",
                 "iridescence_thickness_max")

    base_color: NDArray[np.float32]
    base_color_texture: Optional[Image]
    texcoord: int
    metallic: float
    roughness: float
    emissive: NDArray[np.float32]
    emissive_strength: float
    alpha_mode: AlphaMode
    alpha_cutoff: float
    double_sided: bool
    unlit: bool
    normal_scale: float
    occlusion_strength: float
    ior: float
    specular: float
    specular_color: NDArray[np.float32]
    clearcoat: float
    clearcoat_roughness: float
    sheen_color: NDArray[np.float32]
    sheen_roughness: float
    transmission: float
    thickness: float
    attenuation_color: NDArray[np.float32]
    attenuation_distance: float
    anisotropy_strength: float
    anisotropy_rotation: float
    iridescence: float
    iridescence_ior: float
    iridescence_thickness_min: float
    iridescence_thickness_max: float

    def __init__(self, base_color: Factors = (1.0, 1.0, 1.0, 1.0),
                 base_color_texture: Optional[Image] = None, *, texcoord: int = 0,
                 metallic: float = 1.0, roughness: float = 1.0,
                 emissive: Factors = (0.0, 0.0, 0.0), emissive_strength: float = 1.0,
                 alpha_mode: AlphaMode = "opaque", alpha_cutoff: float = 0.5,
                 double_sided: bool = False, unlit: bool = False, normal_scale: float = 1.0,
                 occlusion_strength: float = 1.0, ior: float = 1.5, specular: float = 1.0,
                 specular_color: Factors = (1.0, 1.0, 1.0), clearcoat: float = 0.0,
                 clearcoat_roughness: float = 0.0, sheen_color: Factors = (0.0, 0.0, 0.0),
                 sheen_roughness: float = 0.0, transmission: float = 0.0,
                 thickness: float = 0.0, attenuation_color: Factors = (1.0, 1.0, 1.0),
                 attenuation_distance: float = 0.0, anisotropy_strength: float = 0.0,
                 anisotropy_rotation: float = 0.0, iridescence: float = 0.0,
                 iridescence_ior: float = 1.3, iridescence_thickness_min: float = 100.0,
                 iridescence_thickness_max: float = 400.0) -> None:
        self.base_color = _factors(base_color, "base_color", 4, 1.0)
        if base_color_texture is not None and not (
                isinstance(base_color_texture, np.ndarray) and base_color_texture.dtype == np.uint8
                and base_color_texture.ndim == 3 and base_color_texture.shape[2] in (3, 4)):
            raise TypeError("base_color_texture: expected an (H, W, 3|4) uint8 array or None")
        self.base_color_texture = base_color_texture
        self.texcoord = int(texcoord)
        self.metallic = float(_factors(metallic, "metallic", 1, 1.0)[0])
        self.roughness = float(_factors(roughness, "roughness", 1, 1.0)[0])
        self.emissive = _factors(emissive, "emissive", 3, np.inf)
        self.emissive_strength = float(_factors(emissive_strength, "emissive_strength", 1,
                                                np.inf)[0])
        if alpha_mode not in ("opaque", "mask", "blend"):
            raise ValueError(f"alpha_mode: must be 'opaque', 'mask' or 'blend', got {alpha_mode!r}")
        self.alpha_mode = alpha_mode
        self.alpha_cutoff = float(alpha_cutoff)
        self.double_sided = bool(double_sided)
        self.unlit = bool(unlit)
        self.normal_scale = float(normal_scale)
        self.occlusion_strength = float(occlusion_strength)
        self.ior = float(_factors(ior, "ior", 1, np.inf)[0])
        if self.ior < 1.0:
            raise ValueError(f"ior: must be >= 1, got {ior!r}")
        self.specular = float(_factors(specular, "specular", 1, 1.0)[0])
        self.specular_color = _factors(specular_color, "specular_color", 3, np.inf)
        self.clearcoat = float(_factors(clearcoat, "clearcoat", 1, 1.0)[0])
        self.clearcoat_roughness = float(_factors(clearcoat_roughness, "clearcoat_roughness", 1,
                                                  1.0)[0])
        self.sheen_color = _factors(sheen_color, "sheen_color", 3, 1.0)
        self.sheen_roughness = float(_factors(sheen_roughness, "sheen_roughness", 1, 1.0)[0])
        self.transmission = float(_factors(transmission, "transmission", 1, 1.0)[0])
        self.thickness = float(_factors(thickness, "thickness", 1, np.inf)[0])
        self.attenuation_color = _factors(attenuation_color, "attenuation_color", 3, 1.0)
        self.attenuation_distance = float(_factors(attenuation_distance, "attenuation_distance",
                                                   1, np.inf)[0])
        self.anisotropy_strength = float(_factors(anisotropy_strength, "anisotropy_strength", 1,
                                                  1.0)[0])
        self.anisotropy_rotation = float(anisotropy_rotation)
        if not np.isfinite(self.anisotropy_rotation):
            raise ValueError(f"anisotropy_rotation: must be finite, got {anisotropy_rotation!r}")
        self.iridescence = float(_factors(iridescence, "iridescence", 1, 1.0)[0])
        self.iridescence_ior = float(_factors(iridescence_ior, "iridescence_ior", 1, np.inf)[0])
        if self.iridescence_ior < 1.0:
            raise ValueError(f"iridescence_ior: must be >= 1, got {iridescence_ior!r}")
        self.iridescence_thickness_min = float(_factors(
            iridescence_thickness_min, "iridescence_thickness_min", 1, np.inf)[0])
        self.iridescence_thickness_max = float(_factors(
            iridescence_thickness_max, "iridescence_thickness_max", 1, np.inf)[0])

    @classmethod
    def _from_factors(cls, factors: Mapping[str, Any],
                      base_color_texture: Optional[Image]) -> Material:
        """From sr_load_scene's material dict (_softrast.load_scene)."""
        slot = factors["base_color_texture"]
        kw = {k: v for k, v in factors.items() if k != "base_color_texture"}
        return cls(base_color_texture=base_color_texture, texcoord=slot["texcoord"] if slot else 0,
                   **kw)

    def __repr__(self) -> str:
        tex = "none" if self.base_color_texture is None else \
            "x".join(map(str, self.base_color_texture.shape[1::-1]))
        return (f"Material(base_color={self.base_color.tolist()}, texture={tex}, "
                f"alpha_mode={self.alpha_mode!r})")


#: Colors and factors: a sequence or array of numbers.
Factors = Union[Sequence[float], NDArray[Any]]


def _factors(value: Union[float, Factors], name: str, count: int,
             high: float) -> NDArray[np.float32]:
    """`count` float32 factors in [0, high], or a ValueError naming `name`
    (a TypeError for booleans, which numpy would read as 0 and 1)."""
    if isinstance(value, (bool, np.bool_)) or (
            isinstance(value, (np.ndarray, list, tuple)) and
            any(isinstance(v, (bool, np.bool_)) for v in np.asarray(value, object).flat)):
        raise TypeError(f"{name}: expected {count} number(s), got bool")
    try:
        a = np.array(value, np.float32).reshape(count)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected {count} number(s), got {value!r}") from None
    if not np.all((a >= 0) & (a <= high)):
        raise ValueError(f"{name}: must be in [0, {high}], got {value!r}")
    return a


def texture_transform(uvs: Any, slot: Optional[Mapping[str, Any]]) -> Any:
    """uvs (N, 2) through a slot's T(offset) R(rotation) S(scale), in the
    library's texture frame ((0, 0) the image's bottom-left)."""
    if slot is None:
        return uvs
    c, s = np.cos(slot["rotation"]), np.sin(slot["rotation"])
    scaled = uvs.astype(np.float64) * slot["scale"]
    out = np.stack([c * scaled[:, 0] - s * scaled[:, 1], s * scaled[:, 0] + c * scaled[:, 1]], -1)
    return (out + slot["offset"]).astype(np.float32)


def material_arrays(arrays: Mapping[str, Any], factors: Mapping[str, Any],
                    texture: Optional[Image]) -> dict[str, Any]:
    """A loaded primitive's Mesh arguments with its material drawn in:
    colors = vertex colors (white without) times the base color factor,
    uvs = the texture's coordinate set through its transform, texture =
    the base color image; alpha dropped for opaque materials."""
    out = {k: v for k, v in arrays.items() if k != "uvs1"}
    slot = factors["base_color_texture"]
    n = len(arrays["vertices"])
    colors = arrays["colors"] if arrays["colors"] is not None else np.ones((n, 4), np.float32)
    colors = colors * np.asarray(factors["base_color"], np.float32)
    if factors["alpha_mode"] == "opaque":
        colors[:, 3] = 1.0
    out["colors"] = colors.astype(np.float32)
    uvs = arrays["uvs1"] if slot and slot["texcoord"] == 1 else arrays["uvs"]
    if texture is not None and uvs is not None:
        out["uvs"] = texture_transform(uvs, slot)
        out["texture"] = np.ascontiguousarray(texture[..., :3]) \
            if factors["alpha_mode"] == "opaque" else texture
    return out
