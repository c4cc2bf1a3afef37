"""The Examples sections of the public API's docstrings run, and print what they say they print."""

import doctest
import importlib

import pytest

#: The modules whose docstrings hold Examples of the public API.
MODULES = [
    "fretting.analysis.methods",
    "fretting.analysis.stress",
    "fretting.engine.choice",
    "fretting.engine.recorder",
    "fretting.engine.runner",
    "fretting.engine.simulation",
    "fretting.engine.stepper",
    "fretting.loading.examples",
    "fretting.loading.history",
    "fretting.loading.history_file",
    "fretting.physics.contact",
    "fretting.physics.profiles",
    "fretting.results.io",
]


@pytest.mark.parametrize("name", MODULES)
def test_examples_pass(name):
    module = importlib.import_module(name)
    failed, attempted = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    assert attempted > 0, f"{name} has no examples"
    assert failed == 0, f"{failed} of {attempted} examples of {name} failed (printed above)"
