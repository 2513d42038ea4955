"""Bounded, strict YAML reading of spec files: whatever the bytes, a Python value or a
``SpecError`` line with the file, line and column — never a traceback, a hang or a memory blow-up.

Limits (a spec is a few hundred bytes; these are generous for hand-written or generated specs):
file size, nesting depth and node count after alias expansion (alias "billion laughs"),
items per list. Duplicate keys, unhashable (list/mapping) keys and non-UTF-8 bytes are refused
with the line they are on. Only a regular file is read, opened without blocking (a named pipe or a
device is refused at once instead of waiting for a writer).

Numbers are YAML 1.2 core numbers (``12``, ``-3.5``, ``1e3``, ``.inf``): YAML 1.1's base-60
(``4:00`` → 240), hexadecimal/octal/binary (``0x78``) and underscored forms stay strings, which the
spec models refuse for numeric fields. YAML 1.1 booleans (``on``/``off``/``yes``/``no``) stay
booleans, accepted by on/off fields only.
"""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

import yaml

MAX_BYTES = 256 * 1024        # spec file size
MAX_DEPTH = 32                # nesting of mappings/lists (after alias expansion)
MAX_NODES = 20_000            # scalars + collections after alias expansion
MAX_ITEMS = 2_000             # items of one list or keys of one mapping


class ReadError(ValueError):
    """One line: where (``line:column``) and what is wrong with the YAML text."""


def _where(mark) -> str:
    return f"line {mark.line + 1}, column {mark.column + 1}" if mark is not None else "unknown position"


INT_12 = re.compile(r"^[-+]?[0-9]+$")
FLOAT_12 = re.compile(r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
                      r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$")


class _Loader(yaml.SafeLoader):
    """SafeLoader with YAML 1.2 core numbers (see the module doc) that bounds nesting while
    composing (the composer recurses per level) and refuses duplicate and unhashable keys."""

    def __init__(self, stream):
        super().__init__(stream)
        self._depth = 0

    def compose_node(self, parent, index):
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                raise ReadError(f"{_where(self.peek_event().start_mark)}: nested deeper than {MAX_DEPTH} levels")
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_mapping(self, node, deep=False):
        seen: dict = {}
        if isinstance(node, yaml.MappingNode):
            for key_node, _ in node.value:          # before merging (<<), whose keys may be overridden
                if key_node.tag == "tag:yaml.org,2002:merge":
                    continue
                if not isinstance(key_node, yaml.ScalarNode):
                    raise ReadError(f"{_where(key_node.start_mark)}: a key must be a plain value, "
                                    "not a list or mapping")
                key = self.construct_object(key_node, deep=deep)
                if key in seen:
                    raise ReadError(f"{_where(key_node.start_mark)}: duplicate key {key!r} "
                                    f"(first at line {seen[key] + 1})")
                seen[key] = key_node.start_mark.line
        return super().construct_mapping(node, deep=deep)


_Loader.yaml_implicit_resolvers = {
    first: [(tag, regexp) for tag, regexp in resolvers
            if tag not in ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}
_Loader.add_implicit_resolver("tag:yaml.org,2002:int", INT_12, list("-+0123456789"))
_Loader.add_implicit_resolver("tag:yaml.org,2002:float", FLOAT_12, list("-+.0123456789"))


def _check_size(root: yaml.Node) -> None:
    """Expanded node count, depth and list lengths of the composed graph (aliases share nodes, so
    memoised sizes make a 10⁹-leaf alias bomb cost a few hundred steps); refuses alias cycles."""
    size: dict[int, int] = {}
    depth: dict[int, int] = {}
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    open_nodes: set[int] = set()
    while stack:
        node, done = stack.pop()
        key = id(node)
        children = _children(node)
        if done:
            open_nodes.discard(key)
            size[key] = 1 + sum(size[id(c)] for c in children)
            depth[key] = 1 + max((depth[id(c)] for c in children), default=0)
            if size[key] > MAX_NODES:
                raise ReadError(f"{_where(node.start_mark)}: expands to more than {MAX_NODES} values "
                                "(aliases included)")
            if depth[key] > MAX_DEPTH:
                raise ReadError(f"{_where(node.start_mark)}: nested deeper than {MAX_DEPTH} levels "
                                "(aliases included)")
            continue
        if key in size:
            continue
        if key in open_nodes:
            raise ReadError(f"{_where(node.start_mark)}: an alias refers to its own anchor (a cycle)")
        if isinstance(node, yaml.CollectionNode) and len(node.value) > MAX_ITEMS:
            raise ReadError(f"{_where(node.start_mark)}: more than {MAX_ITEMS} items in one list or mapping")
        open_nodes.add(key)
        stack.append((node, True))
        stack.extend((c, False) for c in children if id(c) not in size)


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    if isinstance(node, yaml.MappingNode):
        return [n for pair in node.value for n in pair]
    return []


def _read_regular(path: Path) -> bytes:
    """At most MAX_BYTES + 1 bytes of ``path``, which must be a regular file; opened with
    O_NONBLOCK so that a named pipe without a writer cannot block (ReadError otherwise)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY)
    except OSError as exc:
        raise ReadError(f"file: cannot read it ({exc.strerror or exc})") from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            what = ("a folder" if stat.S_ISDIR(mode) else "a named pipe" if stat.S_ISFIFO(mode)
                    else "not a regular file")
            raise ReadError(f"file: {what}; a spec is a regular YAML text file")
        with os.fdopen(fd, "rb", closefd=False) as fh:
            return fh.read(MAX_BYTES + 1)
    except OSError as exc:
        raise ReadError(f"file: cannot read it ({exc.strerror or exc})") from None
    finally:
        os.close(fd)


def read_yaml(path: Path) -> object:
    """The YAML document of ``path`` as Python values, within the limits above (ReadError if not)."""
    raw = _read_regular(path)
    if len(raw) > MAX_BYTES:
        raise ReadError(f"file size: more than {MAX_BYTES // 1024} KiB (a spec is a short text file)")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        raise ReadError(f"line {line}: not UTF-8 text (byte 0x{raw[exc.start]:02x}); save the file as UTF-8") from None
    if "\x00" in text:
        raise ReadError(f"line {text.count(chr(10), 0, text.index(chr(0))) + 1}: NUL character; not a text file")
    try:
        loader = _Loader(text)
    except yaml.reader.ReaderError as exc:          # control characters, checked on construction
        line = text.count("\n", 0, exc.position) + 1
        raise ReadError(f"line {line}: control character #x{exc.character:04x} is not allowed in YAML") from None
    try:
        root = loader.get_single_node()
        if root is None:
            return None
        _check_size(root)
        return loader.construct_document(root)
    except yaml.MarkedYAMLError as exc:
        context = f" ({exc.context} at {_where(exc.context_mark)})" if exc.context and exc.context_mark else ""
        raise ReadError(f"{_where(exc.problem_mark)}: YAML syntax: {exc.problem}{context}") from None
    except yaml.YAMLError as exc:
        raise ReadError(f"YAML: {str(exc).splitlines()[0]}") from None
    except RecursionError:
        raise ReadError(f"nested deeper than {MAX_DEPTH} levels") from None
    finally:
        loader.dispose()
