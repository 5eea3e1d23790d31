"""Scenes: meshes placed by poses, each with an instance ID, and the model readers."""

from __future__ import annotations

import json
import os
import warnings
import math
from typing import TYPE_CHECKING, Any, Iterable, Iterator, List, NamedTuple, Optional, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _softrast
from ._arrays import real_array
from ._camera import Camera
from ._gltf import base_color_images
from ._light import Light
from ._material import Material, material_arrays
from ._softrast import Mesh
from ._warning import warn_lines

if TYPE_CHECKING:
    from .typing import PathLike, RealArrayLike, SceneItem


class Instance:
    """A mesh placed in the world.

    mesh: a :class:`Mesh`.
    pose: (4, 4) or (3, 4) object-to-world matrix (any invertible affine
        map), or None for the identity.
    instance_id: the value of the ``instance_id`` output where this instance
        shows, an int in [0, 2**31); None takes its position in the scene.
    material: the :class:`Material` a model file gave it (already drawn
        into the mesh's colors and texture), or None.
    """

    __slots__ = ("mesh", "pose", "instance_id", "material", "_source")

    mesh: Mesh
    pose: NDArray[np.float64]
    instance_id: Optional[int]
    material: Optional[Material]
    _source: Optional[Tuple[Optional[_SceneFile], int]]

    def __init__(self, mesh: Mesh, pose: Optional[RealArrayLike] = None,
                 instance_id: Optional[int] = None, material: Optional[Material] = None) -> None:
        # (the loaded scene, primitive index) of an instance load made:
        # the file's arrays and textures for shading="pbr".
        self._source = None
        if not isinstance(mesh, Mesh):
            raise TypeError(f"mesh: expected softrast.Mesh, got {type(mesh).__name__}")
        self.mesh = mesh
        self.pose = _pose(pose, "pose")
        if instance_id is not None:
            if not isinstance(instance_id, (int, np.integer)) or isinstance(instance_id, bool):
                raise TypeError(f"instance_id: expected an int, got {type(instance_id).__name__}")
            if not 0 <= instance_id < 2**31:
                raise ValueError(f"instance_id: must be in [0, 2**31), got {instance_id}")
            instance_id = int(instance_id)
        self.instance_id = instance_id
        if material is not None and not isinstance(material, Material):
            raise TypeError(f"material: expected softrast.Material or None, "
                            f"got {type(material).__name__}")
        self.material = material

    def __repr__(self) -> str:
        return f"Instance({self.mesh!r}, instance_id={self.instance_id})"


def _pose(pose: Optional[RealArrayLike], name: str) -> NDArray[np.float64]:
    """A (4, 4) float64 affine matrix from None, (3, 4) or (4, 4)."""
    if pose is None:
        return np.eye(4)
    p = real_array(pose, name)
    if p.shape not in ((4, 4), (3, 4)):
        raise ValueError(f"{name}: shape must be (4, 4) or (3, 4), got {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{name}: contains NaN or infinity")
    if p.shape == (3, 4):
        p = np.vstack([p, [0.0, 0.0, 0.0, 1.0]])
    elif not np.array_equal(p[3], [0.0, 0.0, 0.0, 1.0]):
        raise ValueError(f"{name}: last row must be (0, 0, 0, 1)")
    if abs(np.linalg.det(p[:3, :3])) < 1e-12:
        raise ValueError(f"{name}: the 3x3 part is singular")
    return p


class Animation(NamedTuple):
    """A glTF animation of the file :func:`load` read (``Scene.animations``).

    name: the file's name for it, or "".
    channels: how many node properties it moves.
    duration: seconds, the last key time of its samplers.
    """

    name: str
    channels: int
    duration: float


class Scene:
    """Mesh instances rendered together.

    ``Scene([mesh_a, (mesh_b, pose), Instance(mesh_c, pose, 7)])``; an item
    is a :class:`Mesh` (identity pose), a ``(mesh, pose)`` or ``(mesh, pose,
    instance_id)`` tuple, or an :class:`Instance`.  Instances without an ID
    take their index in the scene.  ``cameras``: the :class:`Camera` list
    of the file :func:`load` read (empty otherwise); ``lights``: its
    :class:`Light` tuple (read-only; given here, or the file's), which
    :func:`render` lights with (its ``lights``); ``variants``: the names of
    its material variants (glTF's KHR_materials_variants), a tuple.
    ``materials``: a file's :class:`Material` list, in the file's order
    (glTF's ``/materials``, without the default material of primitives
    that name none; empty otherwise): :func:`render`'s ``material_id``
    output is the index here of the visible instance's
    ``Instance.material`` (the same object), -1 for one not listed.
    ``animations``: the file's :class:`Animation` list; ``animation`` and
    ``time``: the one :func:`load` posed it by (its index) and when, or
    None and 0.0.  ``metadata``: what a glTF file says about itself (its
    asset's ``version``, ``min_version``, ``generator``, ``copyright``;
    ``xmp``, the KHR_xmp_json_ld packet its asset references as a dict,
    ``xmp_packet`` its index, ``xmp_properties`` its licence and
    authorship properties as text), an empty dict otherwise.
    """

    animations: List[Animation]
    animation: Optional[int]
    time: float
    metadata: dict[str, Any]

    def __init__(self, instances: Iterable[SceneItem] = (), cameras: Iterable[Camera] = (),
                 lights: Iterable[Light] = (), variants: Iterable[str] = (),
                 materials: Iterable[Material] = ()) -> None:
        self.instances: List[Instance] = []
        self.materials: List[Material] = list(materials)
        for i, m in enumerate(self.materials):
            if not isinstance(m, Material):
                raise TypeError(f"materials[{i}]: expected a softrast.Material, "
                                f"got {type(m).__name__}")
        self.cameras = list(cameras)
        self._lights = tuple(lights)
        self.variants: Tuple[str, ...] = tuple(variants)
        self.animations = []
        self.animation = None
        self.time = 0.0
        self.metadata = {}
        # load's reading of a glTF file, for pose: (_SceneFile, material
        # dicts, Materials, base color images); None otherwise.
        self._reading: Optional[Tuple[_SceneFile, List[dict[str, Any]], List[Material],
                                      dict[int, Optional[NDArray[np.uint8]]]]] = None
        for item in instances:
            self.add(item)

    def add(self, item: SceneItem, pose: Optional[RealArrayLike] = None,
            instance_id: Optional[int] = None) -> Instance:
        """Append a Mesh (with ``pose`` and ``instance_id``), a tuple or an Instance."""
        where = f"instances[{len(self.instances)}]"
        if isinstance(item, Instance):
            inst = item
        elif isinstance(item, Mesh):
            inst = Instance(item, pose, instance_id)
        elif isinstance(item, tuple) and 2 <= len(item) <= 3:
            try:
                inst = Instance(*item)
            except (TypeError, ValueError) as e:
                raise type(e)(f"{where}: {e}") from None
        else:
            raise TypeError(f"{where}: expected a Mesh, an Instance or a (mesh, pose[, id]) tuple, "
                            f"got {type(item).__name__}")
        self.instances.append(inst)
        return inst

    def pose(self, animation: Union[int, str, None] = None, time: float = 0.0) -> Scene:
        """This scene posed again, as a new Scene, without reading its file.

        For a Scene :func:`load` made of a glTF file (or one this made):
        ``animation`` (an index into ``animations``, or a name) at ``time``
        seconds, as ``load(path, animation=..., time=...)`` poses it, with
        the very same arrays and matrices (sr_scene_pose); None, the rest
        pose.  The textures are the ones read; the materials' factors,
        the cameras' lenses and the lights are the pose's (glTF's
        KHR_animation_pointer animates them); this scene is left as it is.  ValueError as load's (an
        animation the file does not have, a time that is not finite, a
        time without an animation), and for a scene not read from a glTF
        file.
        """
        time = float(time)
        if not math.isfinite(time):
            raise ValueError(f"time: {time} is not finite")
        if animation is None and time != 0.0:
            raise ValueError("time: a time into an animation: give animation too")
        if self._reading is None:
            raise ValueError("pose: the scene was not read from a glTF file by softrast.load")
        source, _, _, images = self._reading
        index = -1 if animation is None else _animation_in([a.name for a in self.animations],
                                                           animation, source.path)
        d = _softrast.pose_scene(source.capsule, source.path, index, time)
        materials = [Material._from_factors(m, images.get(i))
                     for i, m in enumerate(d["materials"])]
        return _gltf_scene(source.path, source.variant, index, time, d, materials, images)

    @property
    def lights(self) -> Tuple[Light, ...]:
        """The lights of the file :func:`load` read (glTF's
        KHR_lights_punctual, node order), empty otherwise."""
        return self._lights

    def __len__(self) -> int:
        return len(self.instances)

    def __iter__(self) -> Iterator[Instance]:
        return iter(self.instances)

    def __repr__(self) -> str:
        meshes = {id(inst.mesh): inst.mesh for inst in self.instances}
        faces = sum(len(inst.mesh.faces) for inst in self.instances)
        return (f"Scene({_count(len(self.instances), 'instance')} of "
                f"{_count(len(meshes), 'mesh', 'meshes')}, {_count(faces, 'face')} drawn, "
                f"{_count(len(self.cameras), 'camera')})")


def _count(n: int, one: str, many: Optional[str] = None) -> str:
    return f"{n} {one if n == 1 else many or one + 's'}"


def as_scene(scene: Any) -> Scene:
    """A Scene from what render takes: a Mesh, an Instance, a Scene or a list."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, (Mesh, Instance)):
        return Scene([scene])
    if isinstance(scene, (list, tuple)):
        return Scene(scene)
    raise TypeError(f"scene: expected a Mesh, Instance, Scene or list of them, "
                    f"got {type(scene).__name__}")


class _SceneFile:
    """The library's scene of a loaded glTF file (its materials with their
    textures, the primitives' arrays), for shading="pbr".  Pickled as its
    path and material variant: read again where it is unpickled (a Dask
    worker), or, when it cannot be, dropped with a warning (its instances
    then draw their Mesh's base colors)."""

    __slots__ = ("path", "capsule", "variant", "pose")

    def __init__(self, path: Union[str, bytes], capsule: object,
                 variant: Union[str, int, None] = None,
                 pose: Tuple[int, float] = (-1, 0.0)) -> None:
        self.path = path
        self.capsule = capsule
        self.variant = variant
        self.pose = pose   # (animation index or -1, time), as it was read

    def __reduce__(self) -> Tuple[Any, Tuple[Union[str, bytes], Union[str, int, None],
                                             Tuple[int, float]]]:
        return (_read_scene_file, (self.path, self.variant, self.pose))


def _read_scene_file(path: Union[str, bytes], variant: Union[str, int, None] = None,
                     pose: Tuple[int, float] = (-1, 0.0)) -> Optional[_SceneFile]:
    try:
        return _SceneFile(path, _softrast.load_scene(path, variant, *pose)["file"], variant, pose)
    except (OSError, ValueError) as e:
        warnings.warn(f"softrast: {os.fsdecode(path)}: the file's materials are not kept: {e}",
                      stacklevel=2)
        return None


def _path(path: PathLike) -> Union[str, bytes]:
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise TypeError(f"path: expected a str or os.PathLike, got {type(path).__name__}")
    return os.fspath(path)


def load_mesh(path: PathLike) -> Mesh:
    """Read a model file as one :class:`Mesh` (sr_load_mesh).

    Every format the library reads: OBJ (with its MTL's diffuse texture),
    PLY, STL, glTF (the instances of :func:`load`'s scene flattened into
    world space, with the base color image), and through Assimp, when the library
    was built with it, FBX, Collada, 3DS, OFF and more.  Faces with more than three vertices are
    triangulated.  The mesh's one diffuse texture, if any, becomes
    ``Mesh.texture``; a mesh whose parts take different textures keeps none
    (with a warning).  What the reader skips is a :class:`SoftrastWarning`
    each, as :func:`load` gives them.  Raises OSError when the file cannot be read
    (FileNotFoundError when it does not exist) and
    ValueError when it is malformed.
    """
    mesh, lines = _read_mesh(_path(path))
    warn_lines(lines, 2)
    return mesh


def _read_mesh(path: Union[str, bytes]) -> Tuple[Mesh, List[str]]:
    """load_mesh's Mesh and its warnings, not yet given."""
    d = _softrast.load_mesh(path)
    lines = d.pop("warnings")
    return Mesh(**d), lines


def _animation_in(names: List[str], animation: Union[int, str], path: Union[str, bytes]) -> int:
    """load's and Scene.pose's ``animation``: an index as it is (the
    library checks it), a name looked up among the file's ``names``."""
    if isinstance(animation, bool) or not isinstance(animation, (int, str)):
        raise TypeError(f"animation: expected an index or a name, got {type(animation).__name__}")
    if isinstance(animation, int):
        if animation < 0:
            raise ValueError(f"animation: {animation} is not an index (0 is the first)")
        return animation
    if animation not in names:
        listed = ", ".join(repr(n) for n in names) or "none"
        raise ValueError(f"animation: {os.fsdecode(path)} has no animation named "
                         f"{animation!r} (its animations: {listed})")
    return names.index(animation)


def load(path: PathLike, variant: Union[str, int, None] = None,
         animation: Union[int, str, None] = None, time: float = 0.0) -> Scene:
    """Read a model file as a :class:`Scene` (sr_load_scene).

    glTF 2.0 (.gltf, .glb) is read with its node hierarchy: one instance per
    node that draws a mesh primitive, posed by the node's world matrix,
    primitives shared between nodes sharing one :class:`Mesh`.  Each
    primitive's material is drawn into its Mesh as ``render``'s color pass
    takes it: ``colors`` = vertex colors (white without) times the base
    color factor, ``texture`` = the base color texture (its image, with
    ``uvs`` its coordinate set through its KHR_texture_transform); alpha
    is kept for "mask" and "blend" materials, dropped for "opaque" ones.
    The whole material is ``Instance.material``.  Any other format is the
    one mesh of :func:`load_mesh`, with its texture.  A glTF file's
    cameras are ``Scene.cameras``, :class:`Camera` objects in the order
    of softrast render's ``--camera-index`` (node order, depth first):
    ``render(scene, camera=scene.cameras[0], width=..., height=...)``.
    Its KHR_lights_punctual lights are ``Scene.lights``, :class:`Light`
    tuples in world space, which ``render(shading="pbr")`` lights with
    (its ``lights``, as softrast render's ``--lights``).
    A file's material variants (KHR_materials_variants: a product in
    several colourways) are named in ``Scene.variants``; ``variant``, a
    name or a number from 0, draws that one's materials (as softrast
    render's ``--variant``), None each primitive's own.  ValueError names
    the file's variants when it has no such one.

    ``animation`` (an index into the file's animations, or a name) poses
    a glTF file's nodes by that animation at ``time`` seconds, clamped to
    its first and last keys (``softrast render --animation N|NAME --time
    SECONDS``); None draws the rest pose.  ``Scene.animations`` lists the
    file's :class:`Animation` tuples either way.  ValueError for an
    animation the file does not have, a time that is not finite, or an
    animation asked of a format that has none.

    ``Scene.metadata`` is what a glTF file says about itself, for a dataset
    that must keep the licence and authors of its models: the asset's
    ``copyright`` and ``generator`` (None when absent), and ``xmp``, the
    KHR_xmp_json_ld packet the asset references (its ``dc:creator``,
    ``dc:rights``, ``xmpRights:UsageTerms``...) as the file gives it, with
    ``xmp_properties`` those as text; a reference to no packet leaves
    ``xmp`` None, with the reader's warning.

    What the reader skips (a texture it cannot read, an extension it does
    not, a bad reference) is a :class:`SoftrastWarning` each, with the
    text ``softrast`` prints, given at the line that called load.
    """
    scene, lines = _read(_path(path), variant, animation, time)
    warn_lines(lines, 2)
    return scene


def _read(path: Union[str, bytes], variant: Union[str, int, None],
          animation: Union[int, str, None], time: float) -> Tuple[Scene, List[str]]:
    """load's Scene and its warnings (the reader's lines, then the base
    color images left out), not yet given."""
    if variant is not None and (isinstance(variant, bool)
                                or not isinstance(variant, (str, int))):
        raise TypeError(f"variant: expected a str, an int or None, got {type(variant).__name__}")
    time = float(time)
    if not math.isfinite(time):
        raise ValueError(f"time: {time} is not finite")
    if animation is None and time != 0.0:
        raise ValueError("time: a time into an animation: give animation too")
    if isinstance(animation, str):
        # A name is found among the file's animations: the file is read
        # once, at rest, and posed by it (sr_scene_pose), not read twice.
        rest, lines = _read(path, variant, None, 0.0)
        if rest._reading is None:
            _animation_in([], animation, path)
        return rest.pose(animation, time), lines
    index = -1 if animation is None else _animation_in([], animation, path)
    d = _softrast.load_scene(path, variant, index, time)
    if not d["gltf"]:
        # Read again as load_mesh reads it, whose lines are the reader's
        # (the same again) and its texture's.
        mesh, lines = _read_mesh(path)
        return Scene([mesh]), lines
    lines = d["warnings"]
    images = base_color_images(path, d["materials"], lines)
    # The file's /materials, then glTF's default material, which primitives
    # without one draw with (not listed in Scene.materials: no index of
    # the file's).
    materials = [Material._from_factors(m, images.get(i)) for i, m in enumerate(d["materials"])]
    return _gltf_scene(path, variant, index, time, d, materials, images), lines


def _metadata(m: dict[str, Any]) -> dict[str, Any]:
    """load_scene's metadata, the XMP packet (JSON text) read as a dict."""
    return {**m, "xmp": None if m["xmp"] is None else json.loads(m["xmp"])}


def _gltf_scene(path: Union[str, bytes], variant: Union[str, int, None], index: int, time: float,
                d: dict[str, Any], materials: List[Material],
                images: dict[int, Optional[NDArray[np.uint8]]]) -> Scene:
    """The Scene of load_scene's (or pose_scene's) dict: its materials
    and the reading's base color images given, as Scene.pose keeps them."""
    meshes: dict[Tuple[int, int], Mesh] = {}
    instances = []
    source = _SceneFile(path, d["file"], variant, (index, time))
    for primitive, (mesh_index, world, material) in enumerate(d["instances"]):
        key = (mesh_index, material)
        if key not in meshes:
            meshes[key] = Mesh(**material_arrays(d["meshes"][mesh_index], d["materials"][material],
                                                 images.get(material)))
        inst = Instance(meshes[key], world, material=materials[material])
        inst._source = (source, primitive)
        instances.append(inst)
    scene = Scene(instances, [Camera._from_fields(c) for c in d["cameras"]],
                  [Light._from_fields(light) for light in d["lights"]], d["variants"],
                  materials[:-1])
    scene.metadata = _metadata(d["metadata"])
    scene.animations = [Animation(*a) for a in d["animations"]]
    scene.animation = None if index < 0 else index
    scene.time = time if index >= 0 else 0.0
    scene._reading = (source, d["materials"], materials, images)
    return scene
