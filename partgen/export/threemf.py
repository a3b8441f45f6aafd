"""Write a 3MF (core spec 1.x, millimetres) the way slicers read it: one mesh object per distinct
part, named after it, and one build item per copy referencing that object with its placement.

PrusaSlicer and Bambu Studio take an object's name from the ``name`` attribute of ``<object>`` and
make every build item that references one object an instance of it; both read the core spec's
model metadata (``Title``, ``Designer``, ``Description``, ``Application``). Anything else (the part
and its material) goes into the object's ``<metadatagroup>`` under the ``partgen:`` namespace, as
the core spec requires of metadata names it does not define (§3.4.1); consumers ignore what they
do not know.

Written with the standard library rather than trimesh's exporter, which needs lxml and stamps
random UUIDs into every file: the same objects give the same bytes (fixed zip dates, no UUIDs, no
timestamps). Vertices are written as the shortest decimal that reads back to the same float32
when the mesh is float32-exact (the kit's meshes are: they are what the STLs hold), else as the
shortest decimal that reads back to the same double.
"""

from __future__ import annotations

import io
import zipfile
from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

import numpy as np

__all__ = ["Object3MF", "write_3mf", "CORE_NS", "PARTGEN_NS"]

CORE_NS = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
PARTGEN_NS = "urn:partgen:3mf:2025"  # the namespace of partgen's own metadata names

# model metadata names the core spec defines (Table 3-1); any other name gets the partgen: prefix
_WELL_KNOWN = ("Title", "Designer", "Description", "Copyright", "LicenseTerms", "Rating",
               "CreationDate", "ModificationDate", "Application")


@dataclass(frozen=True)
class Object3MF:
    """One mesh object and where its copies go.

    vertices : (n, 3) float, mm; faces : (m, 3) int, outward (counter-clockwise seen from outside).
    transforms : (k, 4, 4) float, one placement per copy, column-vector convention (p' = T p).
    metadata : extra per-object metadata, name -> text (written as ``partgen:<name>``).
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    transforms: tuple[np.ndarray, ...]
    metadata: dict[str, str] = field(default_factory=dict)
    item_names: tuple[str, ...] = ()  # partnumber of each build item (one per transform), optional


_CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" '
    'ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" '
    'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    '</Types>\n')
_RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>\n'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
    '</Relationships>\n')


def _numbers(a: np.ndarray, single: bool = True) -> list[str]:
    """Shortest decimals that read back exactly: float32 ones if ``single`` and ``a`` is
    float32-exact, else double ones."""
    a = np.asarray(a, dtype=np.float64).ravel()
    if not np.all(np.isfinite(a)):
        raise ValueError("a 3MF vertex or transform is not finite")
    a = a + 0.0  # no "-0"
    f = a.astype(np.float32)
    if single and np.array_equal(f.astype(np.float64), a):
        return f.astype(str).tolist()
    return list(map(repr, a.tolist()))


def _transform(t: np.ndarray) -> str:
    """A 4x4 column-vector placement as the spec's "m00 m01 m02 m10 ... m32" (row vectors: the
    3x3 block transposed, then the translation)."""
    t = np.asarray(t, dtype=float)
    if t.shape != (4, 4) or not np.allclose(t[3], (0, 0, 0, 1)):
        raise ValueError("a build item's transform must be an affine 4x4 matrix")
    m = np.vstack([t[:3, :3].T, t[:3, 3]])  # (4, 3): rows m0*, m1*, m2*, m3*
    return " ".join(_numbers(m, single=False))  # placements are doubles: exact as doubles


def _metadata(name: str, value: str, indent: str = "") -> str:
    key = name if name in _WELL_KNOWN else f"partgen:{name}"
    return f'{indent}<metadata name={quoteattr(key)}>{escape(str(value))}</metadata>\n'


def _model_xml(objects: list[Object3MF], model_metadata: dict[str, str]) -> bytes:
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n'
           f'<model unit="millimeter" xml:lang="en-US" xmlns="{CORE_NS}" '
           f'xmlns:partgen="{PARTGEN_NS}">\n']
    out.extend(_metadata(k, v) for k, v in model_metadata.items())
    out.append("<resources>\n")
    for oid, ob in enumerate(objects, start=1):
        v = np.asarray(ob.vertices, dtype=float)
        f = np.asarray(ob.faces, dtype=np.int64)
        if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
            raise ValueError(f"object {ob.name!r}: vertices and faces must be (n, 3)")
        if len(f) and (f.min() < 0 or f.max() >= len(v)):
            raise ValueError(f"object {ob.name!r}: a face refers to a missing vertex")
        out.append(f'<object id="{oid}" name={quoteattr(ob.name)} partnumber={quoteattr(ob.name)} '
                   'type="model">\n')
        if ob.metadata:
            out.append("<metadatagroup>\n")
            out.extend(_metadata(k, v_, " ") for k, v_ in ob.metadata.items())
            out.append("</metadatagroup>\n")
        out.append("<mesh><vertices>\n")
        out.append(('<vertex x="%s" y="%s" z="%s"/>\n' * len(v)) % tuple(_numbers(v)))
        out.append("</vertices><triangles>\n")
        out.append(('<triangle v1="%d" v2="%d" v3="%d"/>\n' * len(f)) % tuple(f.ravel().tolist()))
        out.append("</triangles></mesh></object>\n")
    out.append("</resources>\n<build>\n")
    for oid, ob in enumerate(objects, start=1):
        names = ob.item_names or ("",) * len(ob.transforms)
        if len(names) != len(ob.transforms):
            raise ValueError(f"object {ob.name!r}: {len(names)} item names for "
                             f"{len(ob.transforms)} copies")
        for t, nm in zip(ob.transforms, names):
            pn = f" partnumber={quoteattr(nm)}" if nm else ""
            out.append(f'<item objectid="{oid}" transform="{_transform(t)}"{pn}/>\n')
    out.append("</build>\n</model>\n")
    return "".join(out).encode("utf-8")


def write_3mf(objects: list[Object3MF], metadata: dict[str, str] | None = None) -> bytes:
    """The bytes of a 3MF holding ``objects`` (each one mesh, its copies as build items).

    ``metadata``: model metadata, name -> text; the core spec's names (Title, Designer,
    Description, Application, ...) are written as they are, any other under ``partgen:``.
    """
    names = [ob.name for ob in objects]
    if len(set(names)) != len(names):
        raise ValueError(f"3MF object names must be distinct: {names}")
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for name, text in (("[Content_Types].xml", _CONTENT_TYPES.encode()),
                           ("_rels/.rels", _RELS.encode()),
                           ("3D/3dmodel.model", _model_xml(list(objects), dict(metadata or {})))):
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.create_system = 0
            info.external_attr = 0o644 << 16
            z.writestr(info, text, compresslevel=6)
    return buf.getvalue()
