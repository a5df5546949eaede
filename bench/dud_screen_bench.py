#!/usr/bin/env python3
"""Virtual screening on the six DUD targets or the 17 MUV targets: `surfcomp screen` beside
USRCAT and Open3DAlign.

Per target (../shared/datasets/dud/cmp_list_DUD_<target>_{actives,decoys}.dat.gz, or with
--set muv ../shared/datasets/muv/cmp_list_MUV_<AID>_{actives,decoys}.dat.gz, the same layout):
- the queries are actives picked with random.Random(seed); each gets one conformer (AddHs,
  ETKDGv3 with randomSeed=seed, MMFF94 optimisation) written to its own SDF;
- the library is every other active and the decoys (optionally subsampled with the same
  generator), written in an order the generator shuffles, built once by `surfcomp library
  build --conformers N --seed S` and screened by every query; surfcomp's ranking is the order
  of hits.csv (see `read_hits`); `surfcomp library export` gives the library's conformers, so
  that the baselines score exactly the conformers surfcomp stores;
- the baselines run in the same process on those conformers: USRCAT (GetUSRCAT on heavy atoms,
  GetUSRScore) and Open3DAlign (GetO3A with MMFF94 onto the query, then 1 - ShapeTanimotoDist);
  for every method a molecule's score is its best conformer's;
- metrics per query: ROC AUC (actives against decoys, ties count one half) and EF1% (see
  `enrichment_factor`), averaged over the queries of a target, then over the targets; times per
  library conformer.

With --skip-surfcomp the library conformers come from RDKit in this script (the same recipe as
the queries, N conformers per molecule) and only the baselines run.

Run with the system Python, which has RDKit (Debian python3-rdkit):
    /usr/bin/python3 bench/dud_screen_bench.py --surfcomp build/release/tools/surfcomp --json dud.json
    /usr/bin/python3 bench/dud_screen_bench.py --set muv --max-decoys 1500 --surfcomp ... (MUV,
        a fixed-seed subset of 1,500 decoys per target while developing; every decoy at the end)
"""

import argparse
import csv
import gzip
import json
import math
import random
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from rdkit import Chem, RDLogger
from rdkit.Chem import AllChem, rdDistGeom, rdMolAlign, rdMolDescriptors, rdShapeHelpers

TARGETS = ("ace", "ache", "cdk2", "fxa", "hivrt", "na")
# The 17 MUV targets, by PubChem assay id (Rohrer & Baumann 2009; ../shared/datasets/README.md).
MUV_TARGETS = ("466", "548", "600", "644", "652", "689", "692", "712", "713", "733", "737",
               "810", "832", "846", "852", "858", "859")
SETS = {"dud": TARGETS, "muv": MUV_TARGETS}
METHODS = ("surfcomp", "usrcat", "o3a_shape")
METHOD_LABELS = {"surfcomp": "surfcomp", "usrcat": "USRCAT", "o3a_shape": "O3A-shape"}
EF_FRACTION = 0.01
DEFAULT_DATASETS = Path(__file__).resolve().parent.parent.parent / "shared" / "datasets"


def parse_args(argv=None):
    """Parses the command line into an argparse.Namespace."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--surfcomp", type=Path, help="path of the surfcomp program")
    parser.add_argument("--datasets", type=Path, default=DEFAULT_DATASETS,
                        help="the shared datasets folder holding dud/ (default: ../shared/datasets "
                             "beside the repository)")
    parser.add_argument("--set", choices=sorted(SETS), default="dud",
                        help="the targets' set: dud (six) or muv (17), each in its folder of "
                             "--datasets (default dud)")
    parser.add_argument("--targets", default=None,
                        help="comma-separated targets of the set (default: all of them)")
    parser.add_argument("--queries", type=int, default=5, help="queries per target (default 5)")
    parser.add_argument("--conformers", type=int, default=10,
                        help="conformers per library molecule (default 10)")
    parser.add_argument("--max-actives", type=int, default=None,
                        help="at most this many library actives per target (seeded subsample)")
    parser.add_argument("--max-decoys", type=int, default=None,
                        help="at most this many decoys per target (seeded subsample)")
    parser.add_argument("--seed", type=int, default=42, help="seed of every random choice (default 42)")
    parser.add_argument("--threads", type=int, default=2, help="surfcomp's --threads (default 2)")
    parser.add_argument("--work", type=Path, default=None,
                        help="folder for inputs, libraries and hits (default: a temporary one, removed)")
    parser.add_argument("--json", type=Path, default=None, help="write every figure to this JSON file")
    parser.add_argument("--skip-surfcomp", action="store_true",
                        help="no surfcomp: RDKit library conformers, baselines only")
    parser.add_argument("--skip-o3a", action="store_true", help="no Open3DAlign baseline")
    parser.add_argument("--o3a-workers", type=int, default=1,
                        help="processes for the Open3DAlign baseline (default 1); its time per "
                             "conformer is the processes' CPU time, so it does not depend on this")
    parser.add_argument("--screen-args", default="",
                        help="more arguments for every `surfcomp screen`, as one string "
                             "(e.g. \"--refine 0\")")
    parser.add_argument("--rescreen", action="store_true",
                        help="with --work holding an earlier run of the same settings: keep its "
                             "libraries, conformers and baseline scores, run only the surfcomp "
                             "screens again (with this --surfcomp and --screen-args)")
    parser.add_argument("--rebuild", action="store_true",
                        help="--rescreen, with surfcomp's libraries built again by this --surfcomp "
                             "first (the same conformers, checked against the earlier export)")
    parser.add_argument("--resume", action="store_true",
                        help="with --work: reuse a target's figures from an earlier run of the same "
                             "settings, --screen-args included (WORK/TARGET/result.json), instead "
                             "of running it again; the program itself is not compared")
    args = parser.parse_args(argv)
    known = SETS[args.set]
    args.targets = list(known) if args.targets is None else [t for t in args.targets.split(",") if t]
    for target in args.targets:
        if target not in known:
            parser.error(f"unknown {args.set} target '{target}' (expected some of {', '.join(known)})")
    if args.rebuild:
        args.rescreen = True
    if args.rescreen and (args.work is None or args.skip_surfcomp):
        parser.error("--rescreen and --rebuild need --work (an earlier run's folder) and surfcomp")
    if not args.skip_surfcomp and args.surfcomp is None:
        parser.error("--surfcomp PATH is required unless --skip-surfcomp is given")
    for name in ("queries", "conformers", "threads"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} must be at least 1")
    for name in ("max_actives", "max_decoys"):
        value = getattr(args, name)
        if value is not None and value < 1:
            parser.error(f"--{name.replace('_', '-')} must be at least 1")
    return args


def log(message):
    """Prints a progress line on stderr."""
    print(message, file=sys.stderr, flush=True)


def read_dud_list(path):
    """Reads a DUD list (gzip, tab-separated `Mol_Title ID SMILES`, `#` header).

    Returns a list of dicts with keys title, id, smiles, in file order; the DUD ID is unique
    within a target and serves as the molecule's name throughout.
    """
    records = []
    with gzip.open(path, "rt") as stream:
        for line_number, line in enumerate(stream, start=1):
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            fields = line.split("\t")
            if len(fields) < 3:
                raise ValueError(f"{path}:{line_number}: expected 3 tab-separated fields, got {len(fields)}")
            records.append({"title": fields[0], "id": fields[1], "smiles": fields[2]})
    return records


def seeded_subset(records, limit, rng):
    """Returns at most `limit` records drawn with `rng`, kept in their input order."""
    if limit is None or limit >= len(records):
        return list(records)
    chosen = set(rng.sample(range(len(records)), limit))
    return [r for i, r in enumerate(records) if i in chosen]


def etkdg_parameters(seed):
    """ETKDGv3 parameters with a fixed seed and one thread, so that embedding is reproducible."""
    params = rdDistGeom.ETKDGv3()
    params.randomSeed = seed
    params.numThreads = 1
    return params


def embed_molecule(smiles, name, conformers, seed):
    """Builds a molecule with hydrogens and up to `conformers` ETKDGv3 + MMFF94 conformers.

    Returns the molecule (named `name`), or None when the SMILES cannot be read or no conformer
    can be embedded. A molecule MMFF cannot type keeps its ETKDG coordinates.
    """
    mol = Chem.MolFromSmiles(smiles)
    if mol is None:
        return None
    mol = Chem.AddHs(mol)
    params = etkdg_parameters(seed)
    conformer_ids = list(rdDistGeom.EmbedMultipleConfs(mol, conformers, params))
    if not conformer_ids:
        params.useRandomCoords = True
        conformer_ids = list(rdDistGeom.EmbedMultipleConfs(mol, conformers, params))
    if not conformer_ids:
        return None
    if AllChem.MMFFHasAllMoleculeParams(mol):
        AllChem.MMFFOptimizeMoleculeConfs(mol, numThreads=1)
    mol.SetProp("_Name", name)
    return mol


def choose_queries(actives, count, seed):
    """Picks `count` query actives with random.Random(seed) and gives each one conformer.

    The actives are shuffled by the generator and taken in that order; an active that cannot be
    embedded is passed over. Returns (queries, rng): a list of (record, molecule) and the
    generator, which then draws the library subsamples.
    """
    rng = random.Random(seed)
    order = list(range(len(actives)))
    rng.shuffle(order)
    queries = []
    for index in order:
        if len(queries) == count:
            break
        record = actives[index]
        mol = embed_molecule(record["smiles"], record["id"], 1, seed)
        if mol is not None:
            queries.append((record, mol))
    if len(queries) < count:
        raise RuntimeError(f"only {len(queries)} of the {count} requested queries could be embedded")
    return queries, rng


def write_library_input(records, path):
    """Writes records as a DUD-style `.dat.gz` list; both name columns hold the DUD ID."""
    with open(path, "wb") as raw, gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as stream:
        stream.write(b"# Mol_Title\tID\tSMILES\n")
        for r in records:
            stream.write(f"{r['id']}\t{r['id']}\t{r['smiles']}\n".encode())


def write_query(mol, path):
    """Writes one query molecule (with hydrogens, one conformer) as an SDF."""
    with Chem.SDWriter(str(path)) as writer:
        writer.write(mol)


def run_command(command):
    """Runs a command and returns its wall time in seconds; raises with its stderr on failure."""
    start = time.perf_counter()
    result = subprocess.run([str(c) for c in command], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(str(c) for c in command)} exited with {result.returncode}: "
                           f"{result.stderr.strip()}")
    return elapsed


def read_exported_library(path):
    """Reads `surfcomp library export` output into {name: molecule with all its conformers}.

    Records sharing `surfcomp_name` are conformers of one molecule; they must have the same atoms.
    Hydrogens are kept as written.
    """
    library = {}
    supplier = Chem.SDMolSupplier(str(path), removeHs=False, sanitize=True)
    for index, mol in enumerate(supplier):
        if mol is None:
            raise ValueError(f"{path}: record {index + 1} cannot be read")
        if not mol.HasProp("surfcomp_name"):
            raise ValueError(f"{path}: record {index + 1} has no surfcomp_name tag")
        name = mol.GetProp("surfcomp_name")
        if name not in library:
            library[name] = Chem.Mol(mol)
            continue
        first = library[name]
        if first.GetNumAtoms() != mol.GetNumAtoms():
            raise ValueError(f"{path}: record {index + 1} ({name}) has {mol.GetNumAtoms()} atoms, "
                             f"its first conformer {first.GetNumAtoms()}")
        first.AddConformer(mol.GetConformer(), assignId=True)
    return library


def read_hits(path):
    """Reads a surfcomp hits.csv into {name: row dict}, in the file's order (best first).

    score and fast_score become floats; each row also gets `order_score`, minus the index of
    its group of consecutive rows with equal (stage, score). It follows the file's order, which
    puts the full-match rows (stage 3) before the refined (2) or fast-scored (1) ones whatever
    their score columns, and keeps rows of equal stage and score tied.
    """
    hits = {}
    group = -1
    previous = None
    with open(path, newline="") as stream:
        for row in csv.DictReader(stream):
            for key in ("score", "fast_score"):
                try:
                    row[key] = float(row[key])
                except (KeyError, TypeError, ValueError):
                    row[key] = float("nan")
            if row.get("name") is None:
                raise ValueError(f"{path}: no name column")
            if row["name"] in hits:
                raise ValueError(f"{path}: name {row['name']} appears twice")
            key = (row.get("stage"), row["score"])
            if key != previous:
                group += 1
                previous = key
            row["order_score"] = -float(group)
            hits[row["name"]] = row
    return hits


def usrcat_scores(queries, library):
    """USRCAT similarity of every library molecule to every query, best conformer.

    Descriptors use heavy atoms only. Returns (scores, timing): scores[q][name] and the seconds
    spent on library descriptors and on the query-library scoring.
    """
    start = time.perf_counter()
    library_descriptors = {}
    for name, mol in library.items():
        heavy = Chem.RemoveHs(mol)
        library_descriptors[name] = [rdMolDescriptors.GetUSRCAT(heavy, confId=c.GetId())
                                     for c in heavy.GetConformers()]
    prepare = time.perf_counter() - start
    start = time.perf_counter()
    scores = []
    for query in queries:
        query_descriptor = rdMolDescriptors.GetUSRCAT(Chem.RemoveHs(query))
        scores.append({name: max(rdMolDescriptors.GetUSRScore(query_descriptor, d) for d in descriptors)
                       for name, descriptors in library_descriptors.items()})
    score = time.perf_counter() - start
    return scores, {"prepare_s": prepare, "score_s": score}


def with_hydrogens(mol):
    """Returns the molecule with explicit hydrogens (placed on every conformer if missing)."""
    if all(atom.GetTotalNumHs(includeNeighbors=False) == 0 for atom in mol.GetAtoms()):
        return mol
    return Chem.AddHs(mol, addCoords=True)


# The Open3DAlign worker processes' inputs, set before the pool forks (so nothing is pickled in).
_O3A_QUERIES = None
_O3A_PREPARED = None


def _o3a_chunk(names):
    """Scores of the library molecules `names` against every query (a worker's share): ({q: {name:
    score}}, failed names, CPU seconds)."""
    start = time.process_time()
    queries, query_properties = _O3A_QUERIES
    scores = [dict() for _ in queries]
    failures = set()
    for name in names:
        mol, properties = _O3A_PREPARED[name]
        for q, query in enumerate(queries):
            if properties is None or query_properties[q] is None:
                scores[q][name] = 0.0
                continue
            probe = Chem.Mol(mol)
            best = 0.0
            for conformer in probe.GetConformers():
                cid = conformer.GetId()
                try:
                    alignment = rdMolAlign.GetO3A(probe, query, properties, query_properties[q],
                                                  prbCid=cid, refCid=-1)
                    alignment.Align()
                    similarity = 1.0 - rdShapeHelpers.ShapeTanimotoDist(query, probe, confId2=cid)
                except (RuntimeError, ValueError):
                    failures.add(name)
                    continue
                best = max(best, similarity)
            scores[q][name] = best
    return scores, failures, time.process_time() - start


def o3a_shape_scores(queries, library, workers=1):
    """Open3DAlign (MMFF94) of every library conformer onto each query, then shape Tanimoto.

    The similarity of a conformer is 1 - ShapeTanimotoDist after the alignment; a molecule's is
    its best conformer's. A molecule MMFF cannot type, or whose alignment fails, scores 0 and is
    listed. With workers > 1 the molecules are shared among that many forked processes. Returns
    (scores, timing, failed): scores[q][name]; the seconds spent on the MMFF properties of the
    library, and on aligning and scoring as CPU time summed over the processes (score_s) and as
    wall time (score_wall_s); and the names that scored 0.
    """
    global _O3A_QUERIES, _O3A_PREPARED
    start = time.perf_counter()
    prepared = {}
    failed = []
    for name, mol in library.items():
        mol = with_hydrogens(mol)
        properties = AllChem.MMFFGetMoleculeProperties(mol)
        if properties is None:
            failed.append(name)
        prepared[name] = (mol, properties)
    query_properties = [AllChem.MMFFGetMoleculeProperties(q) for q in queries]
    prepare = time.perf_counter() - start
    _O3A_QUERIES, _O3A_PREPARED = (queries, query_properties), prepared
    names = list(prepared)
    chunks = [names[i::max(1, workers)] for i in range(max(1, workers))]
    start = time.perf_counter()
    if workers > 1:
        import multiprocessing
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            parts = pool.map(_o3a_chunk, chunks)
    else:
        parts = [_o3a_chunk(names)]
    wall = time.perf_counter() - start
    scores = [dict() for _ in queries]
    alignment_failures = set()
    cpu = 0.0
    for part_scores, part_failures, part_cpu in parts:
        for q in range(len(queries)):
            scores[q].update(part_scores[q])
        alignment_failures |= part_failures
        cpu += part_cpu
    _O3A_QUERIES, _O3A_PREPARED = None, None
    failed = sorted(set(failed) | alignment_failures)
    return scores, {"prepare_s": prepare, "score_s": cpu, "score_wall_s": wall}, failed


def roc_auc(scores, labels):
    """ROC AUC of actives (label 1) against decoys (label 0), higher score = more active.

    Mann-Whitney form with mid-ranks: an active-decoy pair with equal scores counts one half.
    """
    scores = np.asarray(scores, dtype=float)
    labels = np.asarray(labels, dtype=bool)
    n_active = int(labels.sum())
    n_decoy = len(labels) - n_active
    if n_active == 0 or n_decoy == 0:
        return float("nan")
    order = np.argsort(scores, kind="stable")
    sorted_scores = scores[order]
    ranks = np.empty(len(scores))
    start = 0
    while start < len(scores):
        end = start
        while end + 1 < len(scores) and sorted_scores[end + 1] == sorted_scores[start]:
            end += 1
        ranks[order[start:end + 1]] = 0.5 * (start + end) + 1.0
        start = end + 1
    rank_sum = ranks[labels].sum()
    return float((rank_sum - n_active * (n_active + 1) / 2.0) / (n_active * n_decoy))


def enrichment_factor(scores, labels, fraction=EF_FRACTION):
    """Enrichment factor at `fraction` of the ranked library (higher score = ranked first).

    With N molecules of which A are active, the top set holds n = ceil(fraction * N) molecules
    and EF = (actives in the top set / n) / (A / N). Molecules tied with the n-th score share the
    remaining places in proportion: the top set counts the actives scored strictly above the
    tie, plus the tie's fraction of actives times the places left, so no order among equal
    scores is assumed.
    """
    scores = np.asarray(scores, dtype=float)
    labels = np.asarray(labels, dtype=bool)
    n = len(scores)
    n_active = int(labels.sum())
    if n == 0 or n_active == 0:
        return float("nan")
    top = math.ceil(fraction * n)
    cut = np.sort(scores)[::-1][top - 1]
    above = scores > cut
    tied = scores == cut
    places_left = top - int(above.sum())
    actives_in_top = labels[above].sum() + places_left * labels[tied].sum() / tied.sum()
    return float((actives_in_top / top) / (n_active / n))


def evaluate(scores, names, active_names):
    """AUC and EF1% of one query's scores over the library `names` (missing names rank last)."""
    values = [scores.get(name, -math.inf) for name in names]
    labels = [name in active_names for name in names]
    return {"auc": roc_auc(values, labels), "ef1": enrichment_factor(values, labels)}


def mean(values):
    """Mean of the finite values (NaN when there is none)."""
    finite = [v for v in values if v is not None and math.isfinite(v)]
    return sum(finite) / len(finite) if finite else float("nan")


def surfcomp_screen(args, target_dir, library_records, queries, query_paths):
    """Builds, exports and screens the surfcomp library of one target.

    Returns (library, scores, details): the exported conformers by name, scores[q][name] from
    the order of hits.csv (see `read_hits`; the first stage's fast_score alone under
    details["fast_scores"]), and the times, counts and build log lines of the run.
    """
    library_input = target_dir / "library.dat.gz"
    write_library_input(library_records, library_input)
    library_path = target_dir / "library.sclib"
    export_path = target_dir / "library.sdf"
    log(f"  surfcomp library build: {len(library_records)} molecules x {args.conformers} conformers")
    build_s = run_command([args.surfcomp, "library", "build", library_input, "-o", library_path,
                           "--conformers", args.conformers, "--seed", args.seed, "--threads", args.threads])
    export_s = run_command([args.surfcomp, "library", "export", library_path, "-o", export_path])
    library = read_exported_library(export_path)
    build_log_path = Path(f"{library_path}.log")
    build_log = build_log_path.read_text().splitlines() if build_log_path.is_file() else []
    scores, fast_scores, screen_s, stages = screen_queries(args, target_dir, library, queries, query_paths)
    details = {"build_s": build_s, "export_s": export_s, "screen_s": screen_s, "hits": stages,
               "fast_scores": fast_scores, "build_log": build_log}
    return library, scores, details


def screen_queries(args, target_dir, library, queries, query_paths):
    """Screens every query against WORK/TARGET/library.sclib: per query the scores from the order
    of hits.csv (see `read_hits`), the fast scores, the screen's time and its rows per stage."""
    library_path = target_dir / "library.sclib"
    scores, fast_scores, screen_s, stages = [], [], [], []
    for q, query_path in enumerate(query_paths):
        hits_path = target_dir / f"hits_{q}.csv"
        log(f"  surfcomp screen query {q + 1}/{len(query_paths)} ({queries[q][0]['id']})")
        screen_s.append(run_command([args.surfcomp, "screen", query_path, library_path, "-o", hits_path,
                                     "--top", 0, "--threads", args.threads] + shlex.split(args.screen_args)))
        hits = read_hits(hits_path)
        missing = sorted(set(library) - set(hits))
        if missing:
            log(f"  warning: {hits_path} lacks {len(missing)} library molecules (ranked last)")
        scores.append({name: row["order_score"] for name, row in hits.items()})
        fast_scores.append({name: row["fast_score"] for name, row in hits.items()
                            if math.isfinite(row["fast_score"])})
        stage_counts = {}
        for row in hits.values():
            stage_counts[row.get("stage", "")] = stage_counts.get(row.get("stage", ""), 0) + 1
        stages.append({"missing": missing, "stages": stage_counts})
    return scores, fast_scores, screen_s, stages


def rescreen_target(args, target, work, earlier):
    """--rescreen: the earlier run's figures of one target with surfcomp's screens run again."""
    target_dir = work / target
    queries = [({"id": query_id}, None) for query_id in earlier["queries"]]
    query_paths = [target_dir / f"query_{q}.sdf" for q in range(len(queries))]
    library = read_exported_library(target_dir / "library.sdf")
    with open(target_dir / "scores.csv", newline="") as stream:
        rows = list(csv.DictReader(stream))
    if not rows:
        raise SystemExit(f"dud_screen_bench: --rescreen: {target_dir / 'scores.csv'} has no molecules")
    names = [row["name"] for row in rows]
    active_ids = {row["name"] for row in rows if row["active"] == "1"}
    log(f"{target}: screening again ({len(names)} molecules)")
    scores = {}
    for method in earlier["per_query"]:
        columns = [f"{method}_q{q}" for q in range(len(queries))]
        if method in ("surfcomp", "surfcomp_fast") or columns[0] not in rows[0]:
            continue
        scores[method] = [{row["name"]: float(row[c]) for row in rows if row[c] != ""} for c in columns]
    timing = dict(earlier["timing"]["surfcomp"])
    if args.rebuild:
        library_path = target_dir / "library.sclib"
        export_path = target_dir / "library_rebuilt.sdf"
        log(f"{target}: building the library again")
        timing["build_s"] = run_command(
            [args.surfcomp, "library", "build", target_dir / "library.dat.gz", "-o", library_path,
             "--conformers", args.conformers, "--seed", args.seed, "--threads", args.threads])
        timing["export_s"] = run_command([args.surfcomp, "library", "export", library_path, "-o", export_path])
        rebuilt = read_exported_library(export_path)
        same = sorted(rebuilt) == sorted(library) and all(
            rebuilt[n].GetNumConformers() == library[n].GetNumConformers() and
            all((rebuilt[n].GetConformer(c.GetId()).GetPositions() == c.GetPositions()).all()
                for c in library[n].GetConformers()) for n in library)
        if not same:
            raise SystemExit(f"dud_screen_bench: --rebuild: {export_path} holds other conformers "
                             f"than {target_dir / 'library.sdf'}; the baselines would not match")
    new_scores, fast_scores, screen_s, stages = screen_queries(args, target_dir, library, queries, query_paths)
    scores = {"surfcomp": new_scores, **({"surfcomp_fast": fast_scores} if all(fast_scores) else {}),
              **scores}
    result = dict(earlier)
    result["timing"] = dict(earlier["timing"])
    result["timing"]["surfcomp"] = dict(timing, screen_s=screen_s)
    result["surfcomp_hits"] = stages
    result["rescreened_with"] = {"surfcomp": str(args.surfcomp), "screen_args": args.screen_args,
                                 "library_rebuilt": bool(args.rebuild)}
    result["mean_before_rescreen"] = earlier.get("mean_before_rescreen", earlier["mean"])
    result["per_query"] = {m: [evaluate(s, names, active_ids) for s in method_scores]
                           for m, method_scores in scores.items()}
    result["mean"] = {m: {k: mean([p[k] for p in per_query]) for k in ("auc", "ef1")}
                      for m, per_query in result["per_query"].items()}
    result["per_conformer_ms"] = per_conformer_times(result["timing"], result["library_conformers"],
                                                     len(queries))
    write_scores(target_dir / "scores.csv", names, active_ids, scores)
    return result


def rdkit_library(args, library_records):
    """Embeds the library with RDKit (for --skip-surfcomp): {name: molecule}, and the time."""
    log(f"  RDKit conformers: {len(library_records)} molecules x {args.conformers} conformers")
    start = time.perf_counter()
    library = {}
    for r in library_records:
        mol = embed_molecule(r["smiles"], r["id"], args.conformers, args.seed)
        if mol is not None:
            library[r["id"]] = mol
    return library, time.perf_counter() - start


def write_scores(path, names, active_names, scores_by_method):
    """Writes every molecule's score per query and method as CSV (one row per molecule)."""
    methods = [m for m in scores_by_method if scores_by_method[m] is not None]
    with open(path, "w", newline="") as stream:
        writer = csv.writer(stream)
        header = ["name", "active"]
        for m in methods:
            header += [f"{m}_q{q}" for q in range(len(scores_by_method[m]))]
        writer.writerow(header)
        for name in names:
            row = [name, int(name in active_names)]
            for m in methods:
                row += [scores_by_method[m][q].get(name, "") for q in range(len(scores_by_method[m]))]
            writer.writerow(row)


RESUMED_SETTINGS = ("queries", "conformers", "max_actives", "max_decoys", "seed", "skip_surfcomp",
                    "skip_o3a", "screen_args")
# What --rescreen needs to match: the libraries, queries and baselines (not the screens).
RESCREEN_SETTINGS = tuple(k for k in RESUMED_SETTINGS if k != "screen_args")


def run_target(args, target, work):
    """Runs the screen of one target and returns its figures as a dict (kept as
    WORK/TARGET/result.json; with --resume, an earlier one of the same settings is reused)."""
    saved = work / target / "result.json"
    settings = {k: getattr(args, k) for k in RESUMED_SETTINGS}
    if args.rescreen:
        earlier = json.loads(saved.read_text()) if saved.is_file() else {}
        earlier_settings = earlier.get("settings") or {}
        if any(earlier_settings.get(k) != settings[k] for k in RESCREEN_SETTINGS):
            raise SystemExit(f"dud_screen_bench: --rescreen: {saved} is missing or of other settings")
        result = rescreen_target(args, target, work, earlier["result"])
        saved.write_text(json.dumps({"settings": settings, "result": result}, indent=1))
        return result
    if args.resume and saved.is_file():
        earlier = json.loads(saved.read_text())
        if earlier.get("settings") == settings:
            log(f"{target}: reusing {saved}")
            return earlier["result"]
    result = run_target_anew(args, target, work)
    saved.write_text(json.dumps({"settings": settings, "result": result}, indent=1))
    return result


def run_target_anew(args, target, work):
    """Runs the screen of one target and returns its figures as a dict."""
    folder = args.datasets / args.set
    prefix = f"cmp_list_{args.set.upper()}_{target}"
    actives = read_dud_list(folder / f"{prefix}_actives.dat.gz")
    decoys = read_dud_list(folder / f"{prefix}_decoys.dat.gz")
    log(f"{target}: {len(actives)} actives, {len(decoys)} decoys")
    queries, rng = choose_queries(actives, args.queries, args.seed)
    query_ids = {r["id"] for r, _ in queries}
    library_actives = seeded_subset([r for r in actives if r["id"] not in query_ids], args.max_actives, rng)
    library_decoys = seeded_subset(decoys, args.max_decoys, rng)
    library_records = library_actives + library_decoys
    rng.shuffle(library_records)
    active_ids = {r["id"] for r in library_actives}

    target_dir = work / target
    target_dir.mkdir(parents=True, exist_ok=True)
    query_mols = [mol for _, mol in queries]
    query_paths = []
    for q, mol in enumerate(query_mols):
        path = target_dir / f"query_{q}.sdf"
        write_query(mol, path)
        query_paths.append(path)

    scores = {m: None for m in METHODS}
    result = {"queries": [r["id"] for r, _ in queries], "timing": {}}
    if args.skip_surfcomp:
        library, embed_s = rdkit_library(args, library_records)
        result["conformer_source"] = "rdkit"
        result["timing"]["rdkit_conformers_s"] = embed_s
    else:
        library, scores["surfcomp"], details = surfcomp_screen(args, target_dir, library_records,
                                                               queries, query_paths)
        result["conformer_source"] = "surfcomp library export"
        result["timing"]["surfcomp"] = {k: details[k] for k in ("build_s", "export_s", "screen_s")}
        result["surfcomp_hits"] = details["hits"]
        result["surfcomp_build_log"] = details["build_log"]
        if all(details["fast_scores"]):
            scores["surfcomp_fast"] = details["fast_scores"]

    names = [r["id"] for r in library_records if r["id"] in library]
    unknown = sorted(set(library) - {r["id"] for r in library_records})
    if unknown:
        raise ValueError(f"{target}: the library holds names not in the input, e.g. {unknown[0]}")
    conformers = sum(library[name].GetNumConformers() for name in names)
    result.update({
        "library_actives": sum(1 for n in names if n in active_ids),
        "library_decoys": sum(1 for n in names if n not in active_ids),
        "library_conformers": conformers,
        "skipped": [r["id"] for r in library_records if r["id"] not in library],
    })
    log(f"  library: {len(names)} molecules, {conformers} conformers, {len(result['skipped'])} skipped")

    log("  USRCAT")
    scores["usrcat"], result["timing"]["usrcat"] = usrcat_scores(query_mols, library)
    if not args.skip_o3a:
        log(f"  Open3DAlign: {conformers} conformers x {len(query_mols)} queries")
        scores["o3a_shape"], result["timing"]["o3a_shape"], result["o3a_failed"] = \
            o3a_shape_scores(query_mols, library, args.o3a_workers)

    result["per_query"] = {}
    result["mean"] = {}
    for method, method_scores in scores.items():
        if method_scores is None:
            continue
        per_query = [evaluate(s, names, active_ids) for s in method_scores]
        result["per_query"][method] = per_query
        result["mean"][method] = {k: mean([p[k] for p in per_query]) for k in ("auc", "ef1")}
    result["per_conformer_ms"] = per_conformer_times(result["timing"], conformers, len(query_mols))
    write_scores(target_dir / "scores.csv", names, active_ids, scores)
    return result


def per_conformer_times(timing, conformers, query_count):
    """Milliseconds per library conformer: build/prepare once, and screen/score per query."""
    if conformers == 0:
        return {}
    times = {}
    if "surfcomp" in timing:
        t = timing["surfcomp"]
        times["surfcomp"] = {"build_ms": 1e3 * t["build_s"] / conformers,
                             "screen_ms": 1e3 * mean(t["screen_s"]) / conformers}
    for method in ("usrcat", "o3a_shape"):
        if method in timing:
            t = timing[method]
            times[method] = {"build_ms": 1e3 * t["prepare_s"] / conformers,
                             "screen_ms": 1e3 * t["score_s"] / (conformers * query_count)}
    if "rdkit_conformers_s" in timing:
        times["rdkit_conformers"] = {"build_ms": 1e3 * timing["rdkit_conformers_s"] / conformers}
    return times


def format_number(value, digits):
    """Formats a float with `digits` decimals, or '-' when it is absent or NaN."""
    if value is None or not math.isfinite(value):
        return "-"
    return f"{value:.{digits}f}"


def summary_table(args, results, means):
    """The stdout report: one row per target, the means over targets, then the times."""
    methods = [m for m in METHODS if m in means]
    lines = []
    lines.append(f"{args.set.upper()} screen: {len(results)} target(s), {args.queries} queries each, "
                 f"{args.conformers} conformers per library molecule, seed {args.seed}")
    lines.append("AUC: actives against decoys, ties one half. EF1%: top ceil(0.01 N) of the N library "
                 "molecules, ties at the cut shared in proportion.")
    header = f"{'target':<7} {'actives':>7} {'decoys':>6} {'confs':>7} |"
    header += "".join(f" {'AUC ' + METHOD_LABELS[m]:>15}" for m in methods) + " |"
    header += "".join(f" {'EF1% ' + METHOD_LABELS[m]:>15}" for m in methods)
    lines.append(header)
    for target, r in results.items():
        row = f"{target:<7} {r['library_actives']:>7} {r['library_decoys']:>6} {r['library_conformers']:>7} |"
        row += "".join(f" {format_number(r['mean'][m]['auc'], 3):>15}" for m in methods) + " |"
        row += "".join(f" {format_number(r['mean'][m]['ef1'], 1):>15}" for m in methods)
        lines.append(row)
    row = f"{'mean':<7} {'':>7} {'':>6} {'':>7} |"
    row += "".join(f" {format_number(means[m]['auc'], 3):>15}" for m in methods) + " |"
    row += "".join(f" {format_number(means[m]['ef1'], 1):>15}" for m in methods)
    lines.append(row)
    lines.append("")
    lines.append("time per library conformer, ms (mean over targets): build or prepare once; screen per query")
    labels = {"surfcomp": f"surfcomp (--threads {args.threads}, wall)",
              "usrcat": "USRCAT (1 thread): descriptor; score",
              "o3a_shape": "O3A-shape (CPU time, 1 thread): MMFF typing; align + shape",
              "rdkit_conformers": "RDKit ETKDG + MMFF conformers (1 thread)"}
    for key, label in labels.items():
        build = mean([r["per_conformer_ms"].get(key, {}).get("build_ms") for r in results.values()])
        screen = mean([r["per_conformer_ms"].get(key, {}).get("screen_ms") for r in results.values()])
        if math.isfinite(build) or math.isfinite(screen):
            lines.append(f"  {label:<52} {format_number(build, 3):>9} {format_number(screen, 3):>9}")
    if "surfcomp_fast" in means:
        lines.append("")
        lines.append(f"surfcomp fast_score of the reported conformers: mean AUC {format_number(means['surfcomp_fast']['auc'], 3)}, "
                     f"mean EF1% {format_number(means['surfcomp_fast']['ef1'], 1)}")
    failed = {t: len(r.get("o3a_failed", [])) for t, r in results.items() if r.get("o3a_failed")}
    if failed:
        lines.append(f"O3A-shape scored 0 (no MMFF typing or failed alignment): {failed}")
    missing = {t: max(len(h["missing"]) for h in r["surfcomp_hits"])
               for t, r in results.items() if any(h["missing"] for h in r.get("surfcomp_hits", []))}
    if missing:
        lines.append(f"surfcomp hits lacking library molecules (ranked last), most over the queries: {missing}")
    skipped = {t: len(r["skipped"]) for t, r in results.items() if r["skipped"]}
    if skipped:
        lines.append(f"library molecules without conformers (left out for every method): {skipped}")
    return "\n".join(lines)


def main(argv=None):
    """Runs the benchmark; returns the process exit status."""
    args = parse_args(argv)
    RDLogger.DisableLog("rdApp.warning")
    RDLogger.DisableLog("rdApp.info")
    if not args.skip_surfcomp and not Path(args.surfcomp).is_file():
        print(f"dud_screen_bench: surfcomp program {args.surfcomp} not found", file=sys.stderr)
        return 2
    folder = args.datasets / args.set
    if not folder.is_dir():
        print(f"dud_screen_bench: {folder} not found; skipped", file=sys.stderr)
        return 0
    temporary = args.work is None
    work = Path(tempfile.mkdtemp(prefix="dud_screen_bench.")) if temporary else args.work
    work.mkdir(parents=True, exist_ok=True)
    try:
        start = time.perf_counter()
        results = {target: run_target(args, target, work) for target in args.targets}
        methods = sorted({m for r in results.values() for m in r["mean"]}, key=lambda m: (m not in METHODS, m))
        means = {m: {k: mean([r["mean"][m][k] for r in results.values() if m in r["mean"]])
                     for k in ("auc", "ef1")} for m in methods}
        total_s = time.perf_counter() - start
    finally:
        if temporary:
            shutil.rmtree(work, ignore_errors=True)
    print(summary_table(args, results, means))
    print(f"total {total_s:.1f} s")
    if args.json is not None:
        config = {k: (str(v) if isinstance(v, Path) else v) for k, v in vars(args).items()}
        config["ef_convention"] = "top set ceil(0.01 N); ties at the cut shared in proportion"
        report = {"config": config, "targets": results, "mean_over_targets": means, "total_s": total_s}
        args.json.write_text(json.dumps(report, indent=1, sort_keys=True) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
