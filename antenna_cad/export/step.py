"""STEP assembly writer: one labelled product per part, millimetres, fixed timestamp.

OCCT's XDE document (XCAFDoc) holds the assembly tree with a name on every product; its
STEPCAFControl writer turns it into AP214 STEP — the calls build123d's ``export_step`` makes,
without build123d.
"""

from __future__ import annotations

import re
from pathlib import Path

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.IFSelect import IFSelect_ReturnStatus
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_Gravity
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_Controller, STEPControl_StepModelType
from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TDataStd import TDataStd_Name
from OCP.TDF import TDF_Label
from OCP.TDocStd import TDocStd_Document
from OCP.XCAFApp import XCAFApp_Application
from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool
from OCP.XSControl import XSControl_WorkSession

from antenna_cad.geometry import kernel
from antenna_cad.geometry.model import Model

STEP_TIMESTAMP = "2000-01-01T00:00:00"     # reproducible bytes: same spec → same file


def write_step(model: Model, name: str, path: Path) -> None:
    """Assembly ``name`` with sub-assemblies ``fabricated`` and ``reference``; parts keep labels."""
    groups = []
    for role in ("fabricated", "reference"):
        children = [_labelled(part.label, kernel.solids(part.shape))
                    for part in sorted((p for p in model.parts if p.role == role), key=lambda p: p.label)]
        if children:
            groups.append((role, children))
    _write(_document((name, groups)), name, path, model.step_pcurves)
    path.write_text(snap_near_zero(_renumber_occurrences(path.read_text())))


def _labelled(label: str, solids) -> tuple:
    """A node (label, solids or children) of the tree. A part of several solids gets one child per
    solid, ``label.1``, ``label.2``, …: OCCT-7 readers (gmsh) name a solid only when its own label
    holds it, and otherwise guess by bounding box (a sheet took its sanding ring's name)."""
    if len(solids) == 1:
        return label, solids
    return label, [(f"{label}.{i}", [s]) for i, s in enumerate(solids, 1)]


def _is_leaf(content) -> bool:
    return not isinstance(content[0], tuple)


def _shape(node) -> kernel.Shape:
    """The compound of a node: its solids (a leaf) or its children's compounds."""
    _, content = node
    return kernel.compound(content if _is_leaf(content) else [_shape(c) for c in content])


def _document(root) -> TDocStd_Document:
    """XDE document in millimetres: the root as a shape, every node below as a component of its
    parent, each named on its instance and on the product it refers to."""
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    app = XCAFApp_Application.GetApplication_s()
    app.NewDocument(TCollection_ExtendedString("MDTV-XCAF"), doc)
    app.InitDocument(doc)
    XCAFDoc_DocumentTool.SetLengthUnit_s(doc, 0.001)
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    tool.SetAutoNaming_s(True)

    def add(node, parent: TDF_Label | None) -> None:
        label = tool.AddShape(_shape(node), False) if parent is None else tool.AddComponent(parent, _shape(node))
        _name(label, node[0])
        if not _is_leaf(node[1]):
            for child in node[1]:
                add(child, _referred(label))

    add(root, None)
    tool.UpdateAssemblies()
    return doc


def _referred(label: TDF_Label) -> TDF_Label:
    """The product a component label refers to (the label itself when it is no reference)."""
    referred = TDF_Label()
    if XCAFDoc_ShapeTool.IsReference_s(label) and XCAFDoc_ShapeTool.GetReferredShape_s(label, referred):
        return referred
    return label


def _name(label: TDF_Label, name: str) -> None:
    TDataStd_Name.Set_s(label, TCollection_ExtendedString(name))
    if XCAFDoc_ShapeTool.IsReference_s(label):
        TDataStd_Name.Set_s(_referred(label), TCollection_ExtendedString(name))


def _write(doc: TDocStd_Document, name: str, path: Path, pcurves: bool) -> None:
    """AP214 STEP of the document: names on, fixed header, p-curves optional (``pcurves``)."""
    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)
    writer = STEPCAFControl_Writer(XSControl_WorkSession(), False)
    writer.SetColorMode(True)
    writer.SetLayerMode(True)
    writer.SetNameMode(True)
    header = APIHeaderSection_MakeHeader(writer.Writer().Model())
    if not header.IsDone():
        header = APIHeaderSection_MakeHeader(0)
        header.Apply(writer.Writer().Model())
    header.SetName(TCollection_HAsciiString(name))
    header.SetTimeStamp(TCollection_HAsciiString(STEP_TIMESTAMP))
    header.SetOriginatingSystem(TCollection_HAsciiString("antenna_cad"))
    STEPCAFControl_Controller.Init_s()
    STEPControl_Controller.Init_s()
    Interface_Static.SetIVal_s("write.surfacecurve.mode", int(pcurves))
    Interface_Static.SetIVal_s("write.precision.mode", 0)
    writer.Transfer(doc, STEPControl_StepModelType.STEPControl_AsIs)
    if writer.Write(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"STEP export failed: {path}")


_TINY = re.compile(r"(?<![\w.])-?\d\.\d*E-(?:[1-9]\d\d|[1-9]\d)\b")    # |x| < 1e-9 (exponent ≤ −10)
_NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0\.(?![\dE])")


def snap_near_zero(text: str) -> str:
    """Reals below 1e-9 (mm, or direction components) written as 0. and −0. as 0.: OCCT's
    parallel booleans leave ±3e-30 or exactly 0 on the same point from run to run, which made
    the STEP (and the STLs) of the same spec differ between builds.

    A match never spans a newline and holds ``E-`` or ``-0.``, so the patterns run only on the
    few lines holding those (found by ``str.find``): same text out, ~40× faster on 20 MB."""
    out, done = [], 0
    for start, stop in _lines_holding(text, ("E-", "-0.")):
        out += [text[done:start], _NEGATIVE_ZERO.sub("0.", _TINY.sub("0.", text[start:stop]))]
        done = stop
    return "".join(out) + text[done:]


def _lines_holding(text: str, needles: tuple[str, ...]) -> list[tuple[int, int]]:
    """(start, stop) of every line of ``text`` holding one of ``needles``, in order, no repeats."""
    spans = set()
    for needle in needles:
        at = text.find(needle)
        while at >= 0:
            start, stop = text.rfind("\n", 0, at) + 1, text.find("\n", at)
            stop = len(text) if stop < 0 else stop
            spans.add((start, stop))
            at = text.find(needle, stop)
    return sorted(spans)


_NAUO = re.compile(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('\d+',(.*?)\);", re.DOTALL)


def _renumber_occurrences(text: str) -> str:
    """OCC numbers assembly occurrences with a process-wide counter, so a second export in the
    same process differs; renumber them 1, 2, … in file order (entity kept on one line)."""
    counter = iter(range(1, 1_000_000))
    return _NAUO.sub(lambda m: "NEXT_ASSEMBLY_USAGE_OCCURRENCE('%d',%s);"
                     % (next(counter), re.sub(r"\s*\n\s*", "", m.group(1))), text)
