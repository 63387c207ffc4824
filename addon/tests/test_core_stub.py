"""The `_core.pyi` stub names what the native module has: every public name of `_core` is in it, and
it names nothing the module lacks (the stub is the contract a reader of engine/ sees)."""

import ast
import os
import unittest

from bake_radiosity.engine import native

STUB = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bake_radiosity", "_core.pyi")


def stub_names():
    names = set()
    with open(STUB) as stub:
        tree = ast.parse(stub.read())
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return {name for name in names if not name.startswith("_")}


class CoreStub(unittest.TestCase):
    def test_the_stub_names_what_the_module_has(self):
        module = {name for name in dir(native.core()) if not name.startswith("_")}
        self.assertEqual(stub_names(), module)


if __name__ == "__main__":
    unittest.main()
