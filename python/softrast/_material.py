"""Materials of loaded scenes: glTF's metallic-roughness factors and base color texture."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping, Optional, Sequence, Union

import numpy as np
from numpy.typing import NDArray

from . import _softrast

if TYPE_CHECKING:
    from .typing import AlphaMode, Image, TextureFilter, TextureWrap


class Material:
    """A glTF 2.0 metallic-roughness material as :func:`softrast.load` reads it
    (the defaults are glTF's).

    base_color: (4,) float32 linear RGBA factor.
    base_color_texture: (H, W, 4) uint8 sRGB image, row 0 at the top, or None.
    texcoord: the texture coordinate set the texture reads (0 or 1).
    texture_filter: how the texture is sampled, "nearest", "bilinear" or
    "trilinear" (a glTF sampler's minFilter, as softrast render reads it).
    wrap_u, wrap_v: outside [0, 1], "repeat", "clamp" (to the edge texels)
    or "mirror" (mirrored repeat): a glTF sampler's wrapS and wrapT.
    metallic, roughness: factors in [0, 1].
    emissive: (3,) float32 linear RGB (times ``emissive_strength``; 0: none).
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
    across a loaded file's thickness texture (0 nm: no film).
    dispersion: 20 / the Abbe number, >= 0 (KHR_materials_dispersion; 0:
    none): a transmissive volume refracts red, green and blue each at its
    own ior.
    diffuse_transmission: the share of the diffuse light let through to the
    other side, in [0, 1] (KHR_materials_diffuse_transmission; 0: none), in
    diffuse_transmission_color, (3,) float32 linear RGB in [0, 1]: leaves,
    paper, lamp shades lit from behind.
    specular_glossiness: the archived KHR_materials_pbrSpecularGlossiness
    model in place of metallic and roughness (and ior's F0 and specular):
    base_color is the diffuse color, sg_specular ((3,) in [0, 1]) the F0
    and glossiness (in [0, 1]) 1 - roughness; the diffuse is weighted by
    1 - max(sg_specular) (docs/pbr.md).

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

    __slots__ = ("base_color", "base_color_texture", "texcoord", "texture_filter", "wrap_u",
                 "wrap_v", "metallic", "roughness",
                 "emissive", "emissive_strength", "alpha_mode", "alpha_cutoff", "double_sided",
                 "unlit", "normal_scale", "occlusion_strength", "ior", "specular",
                 "specular_color", "clearcoat", "clearcoat_roughness", "sheen_color",
                 "sheen_roughness", "transmission", "thickness", "attenuation_color",
                 "attenuation_distance", "anisotropy_strength", "anisotropy_rotation",
                 "iridescence", "iridescence_ior", "iridescence_thickness_min",
                 "iridescence_thickness_max", "dispersion", "diffuse_transmission",
                 "diffuse_transmission_color", "specular_glossiness", "sg_specular",
                 "glossiness")

    base_color: NDArray[np.float32]
    base_color_texture: Optional[Image]
    texcoord: int
    texture_filter: TextureFilter
    wrap_u: TextureWrap
    wrap_v: TextureWrap
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
    dispersion: float
    diffuse_transmission: float
    diffuse_transmission_color: NDArray[np.float32]
    specular_glossiness: bool
    sg_specular: NDArray[np.float32]
    glossiness: float

    def __init__(self, base_color: Factors = (1.0, 1.0, 1.0, 1.0),
                 base_color_texture: Optional[Image] = None, *, texcoord: int = 0,
                 texture_filter: TextureFilter = "trilinear", wrap_u: TextureWrap = "repeat",
                 wrap_v: TextureWrap = "repeat",
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
                 iridescence_thickness_max: float = 400.0, dispersion: float = 0.0,
                 diffuse_transmission: float = 0.0,
                 diffuse_transmission_color: Factors = (1.0, 1.0, 1.0),
                 specular_glossiness: bool = False, sg_specular: Factors = (1.0, 1.0, 1.0),
                 glossiness: float = 1.0) -> None:
        self.base_color = _factors(base_color, "base_color", 4, 1.0)
        if base_color_texture is not None and not (
                isinstance(base_color_texture, np.ndarray) and base_color_texture.dtype == np.uint8
                and base_color_texture.ndim == 3 and base_color_texture.shape[2] in (3, 4)):
            raise TypeError("base_color_texture: expected an (H, W, 3|4) uint8 array or None")
        self.base_color_texture = base_color_texture
        self.texcoord = int(texcoord)
        if texture_filter not in TEXTURE_FILTERS:
            raise ValueError(f"texture_filter: must be one of {', '.join(TEXTURE_FILTERS)}, "
                             f"got {texture_filter!r}")
        for name, wrap in (("wrap_u", wrap_u), ("wrap_v", wrap_v)):
            if wrap not in TEXTURE_WRAPS:
                raise ValueError(f"{name}: must be one of {', '.join(TEXTURE_WRAPS)}, "
                                 f"got {wrap!r}")
        self.texture_filter = texture_filter
        self.wrap_u, self.wrap_v = wrap_u, wrap_v
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
        self.dispersion = float(_factors(dispersion, "dispersion", 1, np.inf)[0])
        self.diffuse_transmission = float(_factors(diffuse_transmission, "diffuse_transmission",
                                                   1, 1.0)[0])
        self.diffuse_transmission_color = _factors(diffuse_transmission_color,
                                                   "diffuse_transmission_color", 3, 1.0)
        self.specular_glossiness = bool(specular_glossiness)
        self.sg_specular = _factors(sg_specular, "sg_specular", 3, 1.0)
        self.glossiness = float(_factors(glossiness, "glossiness", 1, 1.0)[0])

    @classmethod
    def _from_factors(cls, factors: Mapping[str, Any],
                      base_color_texture: Optional[Image]) -> Material:
        """From sr_load_scene's material dict (_softrast.load_scene)."""
        slot = factors["base_color_texture"]
        kw = {k: v for k, v in factors.items() if k != "base_color_texture"}
        if slot:
            kw.update(texcoord=slot["texcoord"], texture_filter=slot["filter"],
                      wrap_u=slot["wrap_u"], wrap_v=slot["wrap_v"])
        return cls(base_color_texture=base_color_texture, **kw)

    def _sampler(self) -> tuple[int, int, int]:
        """(filter, wrap_u, wrap_v) as sr_texture_filter and sr_texture_wrap."""
        return (TEXTURE_FILTERS.index(self.texture_filter) + 1,
                TEXTURE_WRAPS.index(self.wrap_u) + 1, TEXTURE_WRAPS.index(self.wrap_v) + 1)

    def __repr__(self) -> str:
        tex = "none" if self.base_color_texture is None else \
            "x".join(map(str, self.base_color_texture.shape[1::-1]))
        return (f"Material(base_color={self.base_color.tolist()}, texture={tex}, "
                f"alpha_mode={self.alpha_mode!r})")


#: Texture filters and wraps, in sr_texture_filter's and sr_texture_wrap's order.
TEXTURE_FILTERS = ("nearest", "bilinear", "trilinear")
TEXTURE_WRAPS = ("repeat", "clamp", "mirror")

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
    library's texture frame ((0, 0) the image's bottom-left), by the
    library (sr_texture_slot_uv: the coordinates softrast render and the
    physically based program sample)."""
    if slot is None:
        return uvs
    return _softrast.texture_slot_uv(np.ascontiguousarray(uvs, np.float32), slot["offset"],
                                     slot["rotation"], slot["scale"])


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
    # Without set 1 the slot reads set 0, as the library's programs do.
    uvs = arrays["uvs1"] if slot and slot["texcoord"] == 1 and arrays["uvs1"] is not None \
        else arrays["uvs"]
    if texture is not None and uvs is not None:
        out["uvs"] = texture_transform(uvs, slot)
        out["texture"] = np.ascontiguousarray(texture[..., :3]) \
            if factors["alpha_mode"] == "opaque" else texture
    return out
