"""Keyword errors in Python's words (issue 39, item 4). pybind11 answers a misspelt keyword with
"incompatible function arguments" and the whole signature; the wrappers installed here name the
keyword and the known ones instead: "World.step: dtt: no such keyword (known: dt, substeps)".
They also take the old names of renamed keywords (RENAMED). A call that succeeds costs one
Python frame more."""
import functools
import inspect
import warnings

# Keywords renamed so that one quantity has one name across the module (docs/python.md, "One
# name per quantity"): {function or class: {old: new}}. The old name still works and warns
# (DeprecationWarning naming the new one). Fields of the value classes keep theirs in the
# class's `_renamed` (python/py_hand.h, addRenamedField).
RENAMED = {
    "place_hand": {"model": "hand"},
    "HandController": {"model": "hand", "params": "controller"},
}


def _keywords(func):
    """The keywords func takes, or None when it takes any (**kwargs) or has no signature. A
    signature inspect cannot read (a default that is an object) comes from the docstring."""
    try:
        params = inspect.signature(func).parameters.values()
    except (TypeError, ValueError):  # no text signature, or overloaded
        return _doc_keywords(getattr(func, "__doc__", None), getattr(func, "__name__", ""))
    if any(p.kind == p.VAR_KEYWORD for p in params):
        return None
    return [p.name for p in params
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY) and p.name != "self"]


def _doc_keywords(doc, name):
    """The keywords of the signature "name(a, *, b=f(x), ...)" that opens a docstring (pybind11
    constructors and functions whose defaults are objects have none that inspect reads), or
    None (no such line, or **kwargs)."""
    if not name or not (doc or "").startswith(name + "("):
        return None
    names, part, depth = [], "", 0
    for ch in doc[len(name) + 1:]:
        depth += ch in "([{"
        if ch == ")" and depth == 0:
            break
        depth -= ch in ")]}"
        if ch == "," and depth == 0:
            names.append(part.split("=")[0].strip())
            part = ""
        else:
            part += ch
    names.append(part.split("=")[0].strip())
    names = [n for n in names if n not in ("", "*", "/")]
    return None if any(not n.isidentifier() for n in names) else names


def _renamed_keywords(kwargs, renamed, where):
    """kwargs with each old name of `renamed` replaced by its new one, warning about it."""
    for old, new in renamed.items():
        if old in kwargs:
            if new in kwargs:
                raise TypeError(f"{where}: {old}: give {new} only ({old} is its old name)")
            warnings.warn(f"{where}: {old}: deprecated, use {new} "
                          "(one name per quantity: docs/python.md)", DeprecationWarning,
                          stacklevel=3)
            kwargs[new] = kwargs.pop(old)
    return kwargs


def _named(func, where, known=None):
    known = known if known is not None else _keywords(func)
    if known is None:
        return None
    renamed = RENAMED.get(where, {})

    @functools.wraps(func)
    def call(*args, **kwargs):
        kwargs = _renamed_keywords(kwargs, renamed, where)
        try:
            return func(*args, **kwargs)
        except TypeError as error:
            unknown = [k for k in kwargs if k not in known]
            message = str(error)
            if not unknown or not ("incompatible function arguments" in message
                                   or "incompatible constructor arguments" in message):
                raise
            raise TypeError(f"{where}: {unknown[0]}: no such keyword "
                            f"(known: {', '.join(known) or 'none'})") from None
    return call


def name_keywords(module, names):
    """Wraps the public functions, methods (static ones too) and constructors (when the class's
    docstring gives their keywords) of module's `names`."""
    for name in names:
        obj = getattr(module, name)
        if inspect.isclass(obj):
            for attr, raw in list(vars(obj).items()):
                if attr.startswith("_"):
                    continue
                func = raw.__func__ if isinstance(raw, staticmethod) else raw
                if not inspect.isroutine(func):
                    continue
                wrapped = _named(func, f"{name}.{attr}")
                if wrapped is not None:
                    setattr(obj, attr, staticmethod(wrapped) if isinstance(raw, staticmethod)
                            else wrapped)
            known = _doc_keywords(obj.__doc__, name)
            if known is not None and "__init__" in vars(obj):
                obj.__init__ = _named(vars(obj)["__init__"], name, known)
        elif inspect.isroutine(obj):
            wrapped = _named(obj, name)
            if wrapped is not None:
                setattr(module, name, wrapped)
