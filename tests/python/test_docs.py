# help(cablelab) reads well: every public function and method documents its signature first,
# and the package docstring names every public entry.
import inspect
import pydoc

import cablelab


def public_callables():
    for name in cablelab.__all__:
        obj = getattr(cablelab, name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for attr, member in vars(obj).items():
                if not attr.startswith("_") and callable(member) and not isinstance(member, property):
                    yield f"{name}.{attr}", attr, getattr(obj, attr)
        elif callable(obj) and not inspect.isclass(obj):
            yield name, name, obj


def test_every_callable_starts_with_its_signature():
    missing = [full for full, short, obj in public_callables()
               if not (obj.__doc__ or "").lstrip().startswith(short + "(")]
    assert not missing, missing


def test_properties_have_docs():
    for cls in (cablelab.World, cablelab.HandModel, cablelab.ControllerParams):
        for attr, member in vars(cls).items():
            if isinstance(member, property) and not attr.startswith("_"):
                assert member.__doc__, f"{cls.__name__}.{attr}"


def test_help_shows_public_names_without_the_private_module():
    text = pydoc.render_doc(cablelab, renderer=pydoc.plaintext)
    assert "_core." not in text.replace("PACKAGE CONTENTS\n    _core", "")
    assert "object at 0x" not in text
    for name in cablelab.__all__:
        assert name in cablelab.__doc__ or name.isupper(), name


def test_reprs_show_the_fields():
    assert "k=150.0" in repr(cablelab.HandModel())
    assert "kp=0.1" in repr(cablelab.ControllerParams())
    assert "'pulley'" in repr(cablelab.World.load("pulley"))
