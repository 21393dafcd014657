"""Keyword errors in Python's words (issue 39, item 4). pybind11 answers a misspelt keyword with
"incompatible function arguments" and the whole signature; the wrappers installed here name the
keyword and the known ones instead: "World.step: dtt: no such keyword (known: dt, substeps)".
A call that succeeds costs one Python frame more."""
import functools
import inspect


def _keywords(func):
    """The keywords func takes, or None when it takes any (**kwargs) or has no signature."""
    try:
        params = inspect.signature(func).parameters.values()
    except (TypeError, ValueError):  # overloaded: no single signature
        return None
    if any(p.kind == p.VAR_KEYWORD for p in params):
        return None
    return [p.name for p in params
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY) and p.name != "self"]


def _named(func, where):
    known = _keywords(func)
    if known is None:
        return None

    @functools.wraps(func)
    def call(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except TypeError as error:
            unknown = [k for k in kwargs if k not in known]
            if not unknown or "incompatible function arguments" not in str(error):
                raise
            raise TypeError(f"{where}: {unknown[0]}: no such keyword "
                            f"(known: {', '.join(known) or 'none'})") from None
    return call


def name_keywords(module, names):
    """Wraps the public functions and methods (static ones too) of module's `names`."""
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
        elif inspect.isroutine(obj):
            wrapped = _named(obj, name)
            if wrapped is not None:
                setattr(module, name, wrapped)
