"""The type stub ba/python/trigrav.pyi against the module it describes (ba/python/README.md).

The stub is hand-written and checked here in full: drift_from_module(stub) lists every difference
between the stub and the built module, and test_stub_matches_the_module asserts that the list is
empty. What is compared:

* names: the module's public names against the stub's top-level classes, functions and constants,
  both ways; every class's public members (methods, properties, fields, enum values, nested
  classes) both ways, and the dunder methods the stub gives must exist;
* kinds: a function is a `def`, a class a `class`; a static method is `@staticmethod`; a read-write
  attribute (def_readwrite, def_property with a setter) is an annotated field, a read-only one a
  `@property` without setter;
* signatures: parameter names, order, kind (positional or keyword-only after `*`) and defaults of
  every function, method, static method and property getter as pybind11 reports them in the first
  line of __doc__. A default in the stub is a Python expression (0, None, False, 2.0,
  InitialSolver.TRIFOCAL_3PT, RansacOptions()) evaluated in the module's namespace; it must equal
  pybind11's default, itself evaluated the same way. A default pybind11 prints as something that is
  not an expression (an object repr) fails: give the binding a py::arg_v description;
* options classes, whose pybind11 __init__ takes **kwargs (OptionsClass in ba/python/bindings.h):
  the stub's keyword-only parameters are the fields of the class's repr, in that order, and each
  default equals the field of a default-constructed object;
* values: every ClassVar (enum values, class constants) and module constant carries the comment
  `# value = <repr>`, where <repr> is repr() of the module's value, e.g.
      TRIFOCAL_3PT: ClassVar[InitialSolver]  # value = <InitialSolver.TRIFOCAL_3PT: 0>
  (the convention of pybind11-stubgen), so an enum value's name and integer are both checked, and
  the enum's value set is the stub's ClassVar set.

Parameter and return types are not compared (the stub's numpy aliases are not pybind11's names).
TRIGRAV_STUB=<path> checks another stub; `python3 test_stub.py [stub]` prints the drift.
"""

import ast
import inspect
import os
import re
import sys

import pytest

import trigrav

VALUE_COMMENT = re.compile(r"#\s*value\s*=\s*(.*?)\s*$")


def shipped_stub_path():
    """The stub beside the module (the build copies ba/python/trigrav.pyi there)."""
    return os.path.join(os.path.dirname(trigrav.__file__), "trigrav.pyi")


def default_stub_path():
    return os.environ.get("TRIGRAV_STUB") or shipped_stub_path()


# --- pybind11's side --------------------------------------------------------------------------


def split_top_level(text, separator=","):
    """Splits at separators outside brackets and quotes."""
    parts, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            if c == quote and text[i - 1] != "\\":
                quote = None
        elif c in "'\"":
            quote = c
        elif c in "([{<":
            depth += 1
        elif c in ")]}>" and not (c == ">" and text[i - 1] == "-"):
            depth -= 1
        elif c == separator and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return [p.strip() for p in parts if p.strip()]


def pybind_signature(function, name):
    """[(kind, name, default text or None)] from the first line of a pybind11 function's __doc__,
    kind 'positional', 'keyword', 'var_positional' or 'var_keyword'."""
    doc = function.__doc__ or ""
    first = doc.split("\n", 1)[0]
    if not first.startswith(name + "(") or "Overloaded function." in doc:
        raise ValueError(f"no single pybind11 signature in the docstring: {first!r}")
    depth = 0
    for end in range(len(name), len(first)):
        depth += {"(": 1, ")": -1}.get(first[end], 0)
        if depth == 0:
            break
    parameters, kind = [], "positional"
    for part in split_top_level(first[len(name) + 1:end]):
        if part == "*":
            kind = "keyword"
            continue
        if part.startswith("**"):
            parameters.append(("var_keyword", part[2:].split(":")[0].strip(), None))
            continue
        if part.startswith("*"):
            parameters.append(("var_positional", part[1:].split(":")[0].strip(), None))
            kind = "keyword"
            continue
        head, _, default = split_default(part)
        parameters.append((kind, head.split(":")[0].strip(), default.strip() or None))
    return parameters


def split_default(part):
    """'name: type = default' -> ('name: type', '=', 'default'); an '=' in brackets is kept."""
    pieces = split_top_level(part, "=")
    if len(pieces) == 1:
        return part, "", ""
    return pieces[0], "=", "=".join(pieces[1:])


# --- the stub's side --------------------------------------------------------------------------


def stub_signature(node):
    """[(kind, name, default node or None)] of an ast.FunctionDef, as pybind_signature."""
    a = node.args
    parameters = []
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + list(a.defaults)
    parameters += [("positional", p.arg, d) for p, d in zip(positional, defaults)]
    if a.vararg:
        parameters.append(("var_positional", a.vararg.arg, None))
    parameters += [("keyword", p.arg, d) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    if a.kwarg:
        parameters.append(("var_keyword", a.kwarg.arg, None))
    return parameters


def decorators(node):
    return {ast.unparse(d) for d in node.decorator_list}


def is_classvar(annotation):
    return ast.unparse(annotation).startswith(("ClassVar", "typing.ClassVar"))


SAFE_NODES = (ast.Expression, ast.Constant, ast.Name, ast.Attribute, ast.Load, ast.Call,
              ast.Tuple, ast.List, ast.UnaryOp, ast.USub, ast.UAdd)


def evaluate(expression):
    """A default as the module's value: literals, names of the module (enum values, options
    classes called without arguments), tuples and lists of those."""
    tree = ast.parse(expression, mode="eval") if isinstance(expression, str) else \
        ast.Expression(expression)
    for node in ast.walk(tree):
        if not isinstance(node, SAFE_NODES) or (isinstance(node, ast.Call) and
                                                (node.args or node.keywords)):
            raise ValueError(f"not a checkable default: {ast.unparse(tree)}")
    namespace = {k: getattr(trigrav, k) for k in dir(trigrav)}
    namespace["__builtins__"] = {}
    return eval(compile(ast.fix_missing_locations(tree), "<default>", "eval"), namespace)


def same_value(a, b):
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b))
    if type(a).__module__ == "trigrav" and not hasattr(type(a), "__members__"):
        return type(a) is type(b) and repr(a) == repr(b)  # an options object: compare fields
    return type(a) is type(b) and a == b


def value_comment(lines, node):
    match = VALUE_COMMENT.search(lines[node.end_lineno - 1])
    return match.group(1) if match else None


# --- the comparison ---------------------------------------------------------------------------


class Drift:
    def __init__(self, lines):
        self.lines = lines
        self.problems = []

    def report(self, where, message):
        self.problems.append(f"{where}: {message}")

    def signature(self, where, function, name, node, skip_self=False, cls=None):
        try:
            actual = pybind_signature(function, name)
        except ValueError as e:
            return self.report(where, str(e))
        stub = stub_signature(node)
        if skip_self and stub and stub[0][1] == "self":
            stub = stub[1:]
        if skip_self and actual and actual[0][1] in ("self", "arg0"):
            actual = actual[1:]
        if [(k, n) for k, n, _ in actual] == [("var_keyword", "kwargs")] and \
                all(k == "keyword" for k, _, _ in stub):
            return self.options_init(where, cls, stub)
        actual_shape = [(k, n) for k, n, _ in actual]
        stub_shape = [(k, n) for k, n, _ in stub]
        if actual_shape != stub_shape:
            return self.report(where, f"parameters {self.shape(stub_shape)} in the stub, "
                               f"{self.shape(actual_shape)} in the module")
        for (_, pname, actual_default), (_, _, stub_default) in zip(actual, stub):
            self.default(f"{where}({pname})", actual_default, stub_default)

    @staticmethod
    def shape(parameters):
        return "(" + ", ".join(("*" if k == "keyword" else "") + n for k, n in parameters) + ")"

    def default(self, where, actual_text, stub_node):
        if actual_text is None or stub_node is None:
            if (actual_text is None) != (stub_node is None):
                self.report(where, f"default {ast.unparse(stub_node) if stub_node else 'none'} "
                            f"in the stub, {actual_text or 'none'} in the module")
            return
        try:
            actual = evaluate(actual_text)
        except Exception as e:  # pylint: disable=broad-except
            return self.report(where, f"the module's default {actual_text!r} is not an "
                               f"expression of the module ({e}): give it a py::arg_v description")
        self.compare_default(where, actual, stub_node)

    def compare_default(self, where, actual, stub_node):
        try:
            stub = evaluate(stub_node)
        except Exception as e:  # pylint: disable=broad-except
            return self.report(where, f"the stub's default {ast.unparse(stub_node)} cannot be "
                               f"checked ({e})")
        if not same_value(actual, stub):
            self.report(where, f"default {ast.unparse(stub_node)} in the stub, {actual!r} in the "
                        "module")

    def options_init(self, where, cls, stub):
        """An OptionsClass __init__(**kwargs): the stub's keyword parameters are the fields, in the
        order of the class's repr, Name(field=value, ...)."""
        if cls is None:
            return self.report(where, "**kwargs outside a class")
        fields = [k.arg for k in ast.parse(repr(cls()), mode="eval").body.keywords]
        names = [n for _, n, _ in stub]
        if names != fields:
            return self.report(where, f"keyword parameters {names} in the stub, fields {fields} "
                               "in the module")
        instance = cls()
        for _, pname, stub_default in stub:
            if stub_default is None:
                self.report(f"{where}({pname})", "a field without default in the stub")
            else:
                self.compare_default(f"{where}({pname})", getattr(instance, pname), stub_default)

    def constant(self, where, node, value):
        text = value_comment(self.lines, node)
        if text is None:
            self.report(where, f"no '# value = {value!r}' comment in the stub")
        elif text != repr(value):
            self.report(where, f"value {text} in the stub, {value!r} in the module")

    def class_body(self, qualname, node, cls):
        stub_members = {}
        for n in node.body:
            if isinstance(n, (ast.FunctionDef, ast.ClassDef)):
                stub_members.setdefault(n.name, []).append(n)
            elif isinstance(n, ast.AnnAssign):
                stub_members.setdefault(n.target.id, []).append(n)
        public = {m for m in vars(cls) if not m.startswith("_")}
        members = getattr(cls, "__members__", {})
        for name in sorted(public - set(stub_members) - set(members)):
            self.report(f"{qualname}.{name}", "in the module, missing from the stub")
        for name in sorted(set(stub_members) - public):
            if not name.startswith("__") and name not in members:
                self.report(f"{qualname}.{name}", "in the stub, not in the module")
        stub_values = {n.target.id for n in node.body
                       if isinstance(n, ast.AnnAssign) and is_classvar(n.annotation)}
        for name in sorted(set(members) - stub_values):
            self.report(f"{qualname}.{name}", "enum value missing from the stub")
        for name, nodes in stub_members.items():
            where = f"{qualname}.{name}"
            if not hasattr(cls, name):
                if name.startswith("__"):
                    self.report(where, "in the stub, not in the module")
                continue
            self.member(where, cls, name, nodes)

    def member(self, where, cls, name, nodes):
        raw = inspect.getattr_static(cls, name)
        node = nodes[0]
        if isinstance(node, ast.ClassDef):
            if not isinstance(raw, type):
                return self.report(where, "a class in the stub, not in the module")
            return self.class_body(where, node, raw)
        if isinstance(node, ast.AnnAssign):
            if is_classvar(node.annotation):
                if isinstance(raw, property):
                    return self.report(where, "a ClassVar in the stub, a property in the module")
                return self.constant(where, node, getattr(cls, name))
            if not isinstance(raw, property):
                return self.report(where, "a field in the stub, not an attribute in the module")
            if raw.fset is None:
                return self.report(where, "a settable field in the stub, read-only in the module "
                                   "(make it a @property)")
            return self.getter(where, raw, name)
        if "property" in decorators(node):
            if not isinstance(raw, property):
                return self.report(where, "a property in the stub, not in the module")
            has_setter = any(f"{name}.setter" in decorators(n) for n in nodes)
            if (raw.fset is not None) != has_setter:
                return self.report(where, "read-only in the stub, settable in the module (make "
                                   "it a field)" if raw.fset is not None else
                                   "settable in the stub, read-only in the module")
            return self.signature(where, raw.fget, "", node, skip_self=True) \
                if raw.fget.__doc__ and raw.fget.__doc__.startswith("(") else None
        static = "staticmethod" in decorators(node)
        if static != isinstance(raw, staticmethod):
            return self.report(where, "static in the stub only" if static else
                               "static in the module only")
        if isinstance(raw, property):
            return self.report(where, "a method in the stub, a property in the module")
        if len(nodes) > 1:
            return self.report(where, "overloads in the stub: check them by hand")
        function = getattr(cls, name)
        self.signature(where, function, name, node, skip_self=not static, cls=cls)

    def getter(self, where, prop, name):
        doc = prop.fget.__doc__ or ""
        if not doc.startswith("("):
            self.report(where, f"getter without pybind11 signature: {doc.splitlines()[:1]}")


def drift_from_module(stub_path=None):
    """Every difference between the stub at stub_path (default: the one next to the module, or
    $TRIGRAV_STUB) and the module, as 'where: what' strings; [] when they agree."""
    text = open(stub_path or default_stub_path()).read()
    drift = Drift(text.splitlines())
    tree = ast.parse(text)
    stub = {}
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            stub.setdefault(node.name, []).append(node)
        elif isinstance(node, ast.AnnAssign):
            stub.setdefault(node.target.id, []).append(node)
    # Type aliases of the stub (Array = npt.NDArray[...]) are plain assignments: not module names.
    public = {name for name in dir(trigrav) if not name.startswith("_")}
    for name in sorted(public - set(stub)):
        drift.report(name, "in the module, missing from the stub")
    for name in sorted(set(stub) - public):
        drift.report(name, "in the stub, not in the module")
    for name, nodes in stub.items():
        if name not in public:
            continue
        value, node = getattr(trigrav, name), nodes[0]
        if len(nodes) > 1:
            drift.report(name, "given more than once in the stub")
        elif isinstance(node, ast.ClassDef):
            if isinstance(value, type):
                drift.class_body(name, node, value)
            else:
                drift.report(name, "a class in the stub, not in the module")
        elif isinstance(node, ast.FunctionDef):
            if callable(value) and not isinstance(value, type):
                drift.signature(name, value, name, node)
            else:
                drift.report(name, "a function in the stub, not in the module")
        else:
            drift.constant(name, node, value)
    return drift.problems


def test_stub_matches_the_module():
    problems = drift_from_module()
    assert problems == [], "trigrav.pyi differs from the module:\n" + "\n".join(problems)


# Each mutation of the stub, applied to a copy, must be reported (so that the check above cannot
# pass without looking): (what to replace, replacement, a fragment of the expected report).
MUTATIONS = [
    ("    CERES_POINTS_ELIMINATED: ClassVar", "    # CERES_POINTS_ELIMINATED: ClassVar",
     "ThreeViewBundleAdjustmentOptions.Engine.CERES_POINTS_ELIMINATED: enum value missing"),
    ("<FailureCause.STOPPED: 13>", "<FailureCause.STOPPED: 12>",
     "FailureCause.STOPPED: value <FailureCause.STOPPED: 12> in the stub"),
    ("    num_threads: int = 0,\n    return_exceptions", "    num_threads: int = 1,\n"
     "    return_exceptions", "initialize_and_refine_batch(num_threads): default 1 in the stub"),
    ("        max_error: float = 2.0,", "        max_error: float = 2.5,",
     "RansacOptions.__init__(max_error): default 2.5 in the stub"),
    ("        solver: InitialSolver = InitialSolver.TRIFOCAL_3PT,",
     "        solver: InitialSolver = InitialSolver.TRIFOCAL_4PT,",
     "RobustThreeViewOptions.__init__(solver): default InitialSolver.TRIFOCAL_4PT in the stub"),
    ("def solve_essential_8pt(x1: ArrayLike, x2: ArrayLike)",
     "def solve_essential_8pt(x2: ArrayLike, x1: ArrayLike)",
     "solve_essential_8pt: parameters (x2, x1) in the stub, (x1, x2) in the module"),
    ("    def max_angle_deg(self) -> float: ...\n", "",
     "ThreeViewPoseErrors.max_angle_deg: in the module, missing from the stub"),
    ("    def has_bearings(self) -> bool: ...", "    def has_bearings(self, x: int) -> bool: ...",
     "ThreeViewObservations.has_bearings: parameters (x) in the stub, () in the module"),
    ("    cam2_from_cam1: CameraPose\n", "    @property\n    def cam2_from_cam1(self) -> "
     "CameraPose: ...\n", "ThreeViewPose.cam2_from_cam1: read-only in the stub, settable"),
    ("  # value = <LossType.CAUCHY: 2>", "",
     "ThreeViewBundleAdjustmentOptions.LossType.CAUCHY: no '# value = <LossType.CAUCHY: 2>'"),
    ("    def inverse(self) -> CameraPose: ...\n",
     "    def inverse(self) -> CameraPose: ...\n    def is_unit(self) -> bool: ...\n",
     "CameraPose.is_unit: in the stub, not in the module"),
]


@pytest.mark.parametrize("old,new,expected", MUTATIONS, ids=[m[2].split(":")[0] for m in MUTATIONS])
def test_a_mutated_stub_is_reported(tmp_path, old, new, expected):
    text = open(shipped_stub_path()).read()
    assert text.count(old) == 1, f"the mutation's target is not in the stub once: {old!r}"
    mutated = tmp_path / "trigrav.pyi"
    mutated.write_text(text.replace(old, new))
    problems = drift_from_module(str(mutated))
    assert any(expected in p for p in problems), problems


if __name__ == "__main__":
    found = drift_from_module(sys.argv[1] if len(sys.argv) > 1 else None)
    print("\n".join(found) or "the stub matches the module")
    sys.exit(1 if found else 0)
