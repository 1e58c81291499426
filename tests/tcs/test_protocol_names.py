"""The 8 protocol names and what each end may do."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs import Protocol, parse_protocol

NAMES = ["asyn/asyn", "syn/syn", "asyn/syn", "syn/asyn", "asyn/synF", "synF/asyn",
         "asyn/synD", "asyn/synDF"]


def test_exactly_the_eight_protocols_of_the_paper():
    assert [p.value for p in Protocol] == NAMES
    assert all(parse_protocol(name).value == name for name in NAMES)


@pytest.mark.parametrize("name, producer_blocks, consumer_blocks, pull", [
    ("asyn/asyn", False, False, False), ("syn/syn", True, True, False),
    ("asyn/syn", False, True, False), ("syn/asyn", True, False, False),
    ("asyn/synF", False, True, False), ("synF/asyn", True, False, False),
    ("asyn/synD", False, True, True), ("asyn/synDF", False, True, True),
])
def test_which_end_may_block(name, producer_blocks, consumer_blocks, pull):
    protocol = parse_protocol(name)
    assert protocol.producer_may_block is producer_blocks
    assert protocol.consumer_may_block is consumer_blocks
    assert protocol.is_pull is pull


def test_unknown_names_list_the_known_ones():
    with pytest.raises(OrccadError, match=r"unknown protocol 'syn/synF': expected one of "
                                          r"asyn/asyn, syn/syn"):
        parse_protocol("syn/synF")
