"""The chain atlas against the published counts and against independent derivations.

Sources of the numbers asserted here:

* 1, 2, 16, 230, 6856 chains with 4…12 links and the 8-link split 9 + 5 + 2 over the
  mixes (4,4,0), (5,2,1), (6,0,2): the standard number-synthesis tables (Tsai,
  *Mechanism Design: Enumeration of Kinematic Structures According to Function*,
  2001, ch. 3; Sunkari and Schmidt, Mech. Mach. Theory 41, 2006); the mixes
  themselves, the four-bar as the only 4-link chain and Watt/Stephenson as the only
  6-link chains are in Rosenauer's textbook (1938) §§89, 90, 93.
* Watt: 2 inversions (Watt I, II); Stephenson: 3 (Stephenson I, II, III); four-bar: 1.
* Poles n(n-1)/2 and pole lines n(n-1)(n-2)/6: Rosenauer eqs. (42), (43) and his table.
* Everything else is compared with a derivation that does not use the atlas code:
  brute force over link subsets or permutations, or NetworkX's own isomorphism search.
"""

from __future__ import annotations

import itertools
import json
import random
import xml.etree.ElementTree as ET

import networkx as nx
import pytest
import typer
from networkx.algorithms.isomorphism import GraphMatcher
from typer.testing import CliRunner

from linkwork.cli.atlas_cmd import register
from linkwork.topology import atlas
from linkwork.topology.atlas_svg import svg_filename
from linkwork.topology.atlas import (
    Chain,
    canonical_form,
    certificate,
    enumerate_chains,
    find_rigid_subchain,
    identify,
    is_constrained_chain,
    isomorphic,
    link_type_mixes,
    mobility,
    write_atlas_svg,
)

SVG = "{http://www.w3.org/2000/svg}"


# --- independent helpers ------------------------------------------------------------------


def brute_force_rigid(g: nx.Graph) -> bool:
    """Some proper set of >= 2 links spans a sub-chain of mobility 3(k-1) - 2j <= 0."""
    nodes = list(g)
    for k in range(2, len(nodes)):
        for subset in itertools.combinations(nodes, k):
            j = g.subgraph(subset).number_of_edges()
            if 3 * (k - 1) - 2 * j <= 0:
                return True
    return False


def automorphisms_by_permutation(g: nx.Graph) -> list[dict]:
    nodes = sorted(g)
    edges = {frozenset(e) for e in g.edges()}
    found = []
    for perm in itertools.permutations(nodes):
        m = dict(zip(nodes, perm))
        if all(frozenset((m[a], m[b])) in edges for a, b in g.edges()):
            found.append(m)
    return found


def automorphisms_by_vf2(g: nx.Graph) -> list[dict]:
    return list(GraphMatcher(g, g).isomorphisms_iter())


def orbit_counts(g: nx.Graph, autos: list[dict]) -> tuple[int, int]:
    links = {frozenset(m[v] for m in autos) for v in g}
    arcs = [(a, b) for a, b in g.edges()] + [(b, a) for a, b in g.edges()]
    pairs = {frozenset((m[f], m[i]) for m in autos) for f, i in arcs}
    return len(links), len(pairs)


def relabelled(chain: Chain, seed: int) -> nx.Graph:
    rng = random.Random(seed)
    labels = [f"L{i}" for i in range(chain.n_links)]
    rng.shuffle(labels)
    g = nx.relabel_nodes(chain.graph(), dict(zip(range(1, chain.n_links + 1), labels)))
    shuffled = nx.Graph()
    nodes = list(g)
    rng.shuffle(nodes)
    shuffled.add_nodes_from(nodes)
    edges = list(g.edges())
    rng.shuffle(edges)
    shuffled.add_edges_from(edges)
    return shuffled


# --- counts ---------------------------------------------------------------------------------


@pytest.mark.parametrize(("n_links", "published"), [(4, 1), (6, 2), (8, 16), (10, 230)])
def test_counts_match_published_numbers(n_links, published):
    assert len(enumerate_chains(n_links)) == published


def test_twelve_links_match_published_count():
    # (its time is measured by `atlas --links 12`, not asserted here: bench/README.md)
    atlas._cache.pop(12, None)  # a fresh build
    chains = enumerate_chains(12)
    assert len(chains) == 6856


def test_link_type_mixes_are_rosenauers():
    # Rosenauer §89-§93: four-bar all binary; 6 links: n2 = 4, n3 = 2; 8 links: three mixes.
    assert link_type_mixes(4) == [(4,)]
    assert link_type_mixes(6) == [(4, 2)]
    assert link_type_mixes(8) == [(4, 4, 0), (5, 2, 1), (6, 0, 2)]
    # Eq. (48): n2 = 4 + sum (i - 3) n_i for every mix, and the Grübler hinge count.
    for n in (10, 12):
        for mix in link_type_mixes(n):
            assert sum(mix) == n
            assert mix[0] == 4 + sum((i - 3) * c for i, c in enumerate(mix, start=2) if i > 3)
            assert sum(i * c for i, c in enumerate(mix, start=2)) == 2 * (3 * n // 2 - 2)


def test_eight_link_mix_split_is_9_5_2():
    split: dict[tuple[int, ...], int] = {}
    for chain in enumerate_chains(8):
        split[chain.mix] = split.get(chain.mix, 0) + 1
    assert split == {(4, 4, 0): 9, (5, 2, 1): 5, (6, 0, 2): 2}


def test_mix_field_matches_the_graph():
    for chain in enumerate_chains(10):
        degrees = list(chain.link_types.values())
        assert tuple(degrees.count(t) for t in range(2, 6)) == chain.mix


# --- every chain is a constrained chain without rigid sub-chains ----------------------------


@pytest.mark.parametrize("n_links", [4, 6, 8])
def test_chains_have_mobility_one_and_no_rigid_subchain_by_brute_force(n_links):
    for chain in enumerate_chains(n_links):
        g = chain.graph()
        assert mobility(g) == 1
        assert chain.n_hinges == 3 * n_links // 2 - 2
        assert nx.is_biconnected(g)
        assert not brute_force_rigid(g)


def test_pebble_game_agrees_with_brute_force_on_random_graphs():
    rng = random.Random(20260521)
    agree = 0
    for _ in range(400):
        n = rng.choice([6, 8])
        m = 3 * n // 2 - 2
        pairs = list(itertools.combinations(range(n), 2))
        g = nx.Graph(rng.sample(pairs, m))
        g.add_nodes_from(range(n))
        expected = brute_force_rigid(g) or 3 * (n - 1) - 2 * m <= 0
        found = find_rigid_subchain(g)
        assert (found is not None) == expected
        if found is not None:
            # The reported links really are a structure (mobility <= 0).
            sub = g.subgraph(found)
            assert 3 * (len(found) - 1) - 2 * sub.number_of_edges() <= 0
        agree += 1
    assert agree == 400


def test_triangle_is_found_and_chain_rejected():
    # Triangle 1-2-3 closed by the loop 3-4-5-6-1: Grübler mobility 1, but a rigid triangle.
    g = nx.Graph([(1, 2), (2, 3), (1, 3), (3, 4), (4, 5), (5, 6), (6, 1)])
    assert mobility(g) == 1
    assert find_rigid_subchain(g) == frozenset({1, 2, 3})
    assert not is_constrained_chain(g)
    with pytest.raises(ValueError):
        identify(g)


def test_double_hinge_is_refused():
    with pytest.raises(ValueError):
        is_constrained_chain([(1, 2), (1, 2)])


# --- isomorphism ----------------------------------------------------------------------------


@pytest.mark.parametrize("n_links", [6, 8, 10])
def test_atlas_chains_are_pairwise_non_isomorphic(n_links):
    graphs = [c.graph() for c in enumerate_chains(n_links)]
    for a, b in itertools.combinations(graphs, 2):
        assert not nx.is_isomorphic(a, b)


@pytest.mark.parametrize("n_links", [6, 8, 10, 12])
def test_relabelled_chain_collapses_to_the_same_canonical_form(n_links):
    chains = enumerate_chains(n_links)
    rng = random.Random(n_links)
    for chain in rng.sample(chains, min(12, len(chains))):
        other = relabelled(chain, rng.randrange(10**6))
        assert isomorphic(chain, other)
        assert certificate(other) == certificate(chain)
        assert identify(other) == chain
        assert canonical_form(other) == chain.edges


def test_watt_and_stephenson_are_different_chains():
    watt, stephenson = enumerate_chains(6)
    assert not isomorphic(watt, stephenson)
    assert canonical_form(watt) != canonical_form(stephenson)


# --- names, inversions, input choices -------------------------------------------------------


def test_six_link_names_follow_ternary_adjacency():
    chains = {c.name: c for c in enumerate_chains(6)}
    assert set(chains) == {"Watt", "Stephenson"}
    for name, chain in chains.items():
        ternary = [v for v, d in chain.link_types.items() if d == 3]
        adjacent = chain.graph().has_edge(*ternary)
        assert adjacent == (name == "Watt")


def test_published_inversion_counts():
    (four_bar,) = enumerate_chains(4)
    assert four_bar.name == "four-bar"
    assert four_bar.n_inversions == 1
    chains = {c.name: c for c in enumerate_chains(6)}
    assert chains["Watt"].n_inversions == 2
    assert chains["Stephenson"].n_inversions == 3


@pytest.mark.parametrize("n_links", [4, 6])
def test_inversions_and_input_choices_by_permutation_brute_force(n_links):
    for chain in enumerate_chains(n_links):
        g = chain.graph()
        assert (chain.n_inversions, chain.n_input_choices) == orbit_counts(g, automorphisms_by_permutation(g))


@pytest.mark.parametrize("n_links", [8, 10])
def test_inversions_and_input_choices_by_networkx_automorphisms(n_links):
    for chain in enumerate_chains(n_links):
        g = chain.graph()
        assert (chain.n_inversions, chain.n_input_choices) == orbit_counts(g, automorphisms_by_vf2(g))


def test_orbits_partition_links_and_frame_input_pairs():
    for chain in enumerate_chains(8):
        links = sorted(v for orbit in chain.inversions for v in orbit)
        assert links == list(range(1, chain.n_links + 1))
        pairs = sorted(p for orbit in chain.input_choices for p in orbit)
        assert pairs == sorted([(a, b) for a, b in chain.edges] + [(b, a) for a, b in chain.edges])


def test_poles_pole_lines_and_loops():
    # Rosenauer §84-§85: P = n(n-1)/2, T = n(n-1)(n-2)/6; 6 links: 15 and 20, 8 links: 28 and 56.
    watt = enumerate_chains(6)[0]
    assert (watt.poles, watt.pole_lines, watt.loops) == (15, 20, 2)
    eight = enumerate_chains(8)[0]
    assert (eight.poles, eight.pole_lines, eight.loops) == (28, 56, 3)
    # Independent loops = j - n + 1 = n/2 - 1 for every chain.
    assert all(c.loops == 4 for c in enumerate_chains(10))


def test_to_dict_is_json_ready():
    chain = enumerate_chains(6)[1]
    doc = json.loads(json.dumps(chain.to_dict()))
    assert doc["label"] == chain.label
    assert doc["mix"] == {"binary": 4, "ternary": 2}
    assert doc["name"] == "Stephenson"
    assert doc["n_inversions"] == 3
    assert len(doc["hinges"]) == 7


def test_bad_link_counts_raise():
    for bad in (2, 5, 7, 14):
        with pytest.raises(ValueError):
            enumerate_chains(bad)


def test_progress_bar_build_gives_the_same_atlas():
    built = atlas._build(8, progress=True)
    assert list(built) == enumerate_chains(8)


# --- SVG ------------------------------------------------------------------------------------


@pytest.mark.parametrize("n_links", [4, 6, 8])
def test_svg_is_valid_xml_with_one_shape_per_link_and_one_circle_per_hinge(tmp_path, n_links):
    chains = enumerate_chains(n_links)
    paths = write_atlas_svg(chains, tmp_path / "svg")
    assert len(paths) == len(chains) == len(set(paths))
    for chain, path in zip(chains, paths):
        root = ET.parse(path).getroot()
        assert root.tag == SVG + "svg"
        bars = root.findall(f".//{SVG}line")
        plates = root.findall(f".//{SVG}polygon")
        circles = root.findall(f".//{SVG}circle")
        assert len(bars) + len(plates) == chain.n_links
        assert len(circles) == chain.n_hinges
        types = chain.link_types
        assert len(bars) == sum(1 for d in types.values() if d == 2)
        for plate in plates:
            link = int(plate.get("id").removeprefix("link-"))
            assert len(plate.get("points").split()) == types[link]


# --- CLI ------------------------------------------------------------------------------------


@pytest.fixture()
def cli():
    app = typer.Typer()

    @app.callback()
    def main() -> None:  # keeps "atlas" a sub-command
        pass

    register(app)
    runner = CliRunner()
    return lambda *args: runner.invoke(app, list(args))


def test_cli_json(cli):
    r = cli("atlas", "--links", "8", "--format", "json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["count"] == 16
    assert doc["by_mix"] == {"4/4/0": 9, "5/2/1": 5, "6/0/2": 2}
    assert len(doc["chains"]) == 16


def test_cli_table_and_svg(cli, tmp_path):
    r = cli("atlas", "--links", "6", "--svg", str(tmp_path))
    assert r.exit_code == 0, r.output
    assert "Watt" in r.stdout and "Stephenson" in r.stdout
    assert len(list(tmp_path.glob("*.svg"))) == 2


@pytest.mark.parametrize("bad", ["5", "2", "14", "0", "-4"])
def test_cli_rejects_bad_link_counts_with_one_message(cli, bad):
    r = cli("atlas", "--links", bad)
    assert r.exit_code == 2
    assert "Traceback" not in r.output
    assert "--links" in r.output


# --- SVG output safety (issue 10): every sketch whole or not at all, errors one line -----------


def _full_disk_after(monkeypatch, n_ok: int) -> None:
    """Make the n_ok+1-th file the atomic writer opens fail half-way with ENOSPC."""
    import builtins
    import errno
    import os

    import linkwork.outputs

    opened = []

    class Half:
        def __init__(self, fh):
            self.fh = fh

        def write(self, text):
            self.fh.write(text[: len(text) // 2])
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.fh.close()

    def fake_open(path, mode="r", **kw):
        fh = builtins.open(path, mode, **kw)
        opened.append(path)
        return fh if len(opened) <= n_ok else Half(fh)

    monkeypatch.setattr(linkwork.outputs, "open", fake_open, raising=False)


def test_svg_full_disk_keeps_the_previous_sketch_and_leaves_no_part(tmp_path, monkeypatch):
    from linkwork.errors import OutputError

    chains = enumerate_chains(6)
    names = [svg_filename(c) for c in chains]
    (tmp_path / names[1]).write_text("previous\n")
    _full_disk_after(monkeypatch, 1)
    with pytest.raises(OutputError, match="No space left on device") as exc:
        write_atlas_svg(chains, tmp_path)
    assert names[1] in str(exc.value)
    assert (tmp_path / names[1]).read_text() == "previous\n"
    assert ET.parse(tmp_path / names[0]).getroot().tag == SVG + "svg"  # the first one is whole
    assert [p.name for p in tmp_path.iterdir() if ".part" in p.name] == []


def test_cli_svg_errors_are_one_line(cli, tmp_path, monkeypatch):
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    r = cli("atlas", "--links", "4", "--svg", str(blocker / "sub"))
    assert r.exit_code == 2 and (r.exception is None or isinstance(r.exception, SystemExit))
    assert "Traceback" not in r.output
    assert f"cannot write SVG files to '{blocker / 'sub'}'" in r.output
    _full_disk_after(monkeypatch, 0)
    r = cli("atlas", "--links", "4", "--svg", str(tmp_path / "svg"))
    assert r.exit_code == 2, r.output
    assert "No space left on device" in r.output and "Traceback" not in r.output
    assert [p.name for p in (tmp_path / "svg").iterdir()] == []


@pytest.mark.parametrize("n_links", [8, 10, 12])
def test_contracted_graph_automorphisms_equal_a_graph_matcher_search(n_links):
    """`atlas_contracted.automorphisms` (backtracking on the multiplicity matrix) against the
    automorphisms of the subdivided graph found by NetworkX's VF2 matcher: the same set."""
    from linkwork.topology.atlas_contracted import work_units

    units = [u for u in work_units(n_links) if u.graph is not None]
    assert units
    for unit in units:
        cg = unit.graph
        s = nx.Graph()
        for v, t in enumerate(cg.types):
            s.add_node(("v", v), kind=f"v{t}")
        for e, (a, b) in enumerate(cg.edges):
            s.add_node(("e", e), kind="e")
            s.add_edges_from([(("v", a), ("e", e)), (("v", b), ("e", e))])
        vf2 = {(tuple(iso[("v", v)][1] for v in range(len(cg.types))),
                tuple(iso[("e", e)][1] for e in range(len(cg.edges))))
               for iso in GraphMatcher(s, s, node_match=lambda x, y: x["kind"] == y["kind"])
               .isomorphisms_iter()}
        assert set(cg.automorphisms) == vf2
        assert len(cg.automorphisms) == len(vf2)  # no automorphism twice
