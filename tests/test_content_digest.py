"""Generated code is named by what it is made of (seahelm._codegen.content_digest).

Nine places named their generated modules or keyed their caches with the same idiom (SHA-1 of
the parts joined by NUL bytes, 16 hex digits); one helper now, which gives the names the idiom
gave (a new name would be a recompile on every machine: with a warm kernel cache, the tests of
the kernels, row loops, guided, state-space, wave-filter and environment-stage code compiled
nothing new after the change).
"""

from __future__ import annotations

import hashlib

from seahelm._codegen import content_digest


def test_the_digest_is_sha1_of_the_parts_joined_by_nul():
    expected = hashlib.sha1(b"source\0" + b"\x01\x02" + b"\0v1").hexdigest()[:16]
    assert content_digest("source", b"\x01\x02", "v1") == expected
    assert len(expected) == 16 and int(expected, 16) >= 0


def test_every_part_and_where_it_ends_changes_the_digest():
    base = content_digest("ab", "c")
    assert content_digest("a", "bc") != base  # (the separator keeps parts apart)
    assert content_digest("ab", "d") != base
    assert content_digest("ab", "c", "") != base
    assert content_digest("ab", b"c") == base  # (str parts are their UTF-8 bytes)
    assert content_digest("ä") == hashlib.sha1("ä".encode()).hexdigest()[:16]
