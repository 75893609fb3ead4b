"""Mutation testing of the methods layer with mutmut: ``make mutate`` (not part of ``make test``).

Each module of ``modules.toml`` is mutated alone, in a scratch copy of the package under
``_build/mutation/<module>/``, and every mutant is run against the module's own tests and its
doctests (mutmut 3 runs, for a mutant of a function, only the tests that called that function on
the clean code; pytest stops at the first failure). The results are written to ``results.json``
and rendered, with the equivalent mutants of ``equivalents.toml`` (each with its reason), into
``bench/mutation.md``. ``bench/mutation/test_report.py`` checks that the report covers the modules
as they are now: each module's files are recorded with a content hash, so a module changed
without a new run fails that test.

    python bench/mutation/mutate.py run [MODULE ...]     # mutate (all modules by default)
    python bench/mutation/mutate.py retry MODULE ...     # keep the results of unchanged code,
                                                         # run the new mutants and the survivors
    python bench/mutation/mutate.py report               # render the report again
    python bench/mutation/mutate.py survivors MODULE     # the surviving mutants' diffs
"""

import argparse
import ast
import glob
import hashlib
import json
import os
import shutil
import subprocess
import sys
import time
import tokenize
import tomllib
from io import StringIO
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
MODULES = HERE / "modules.toml"
EQUIVALENTS = HERE / "equivalents.toml"
RESULTS = HERE / "results.json"
REPORT = ROOT / "bench" / "mutation.md"
SCRATCH = ROOT / "_build" / "mutation"
PACKAGE = ROOT / "pkg"

# mutmut's exit-code vocabulary, reduced to the report's: a mutant is killed (a test failed, or it
# ran out of time: an infinite loop is a detected bug), survived, or was not run by any test.
KILLED, SURVIVED, NO_TESTS = "killed", "survived", "no tests"
STATUS = {1: KILLED, 3: KILLED, 36: KILLED, 24: KILLED, -24: KILLED, 152: KILLED, 255: KILLED,
          -11: KILLED, -9: KILLED, 0: SURVIVED, 5: NO_TESTS, 33: NO_TESTS}
# The kill rate every module must reach: killed / (mutants - equivalent).
REQUIRED = 0.90


def modules():
    """The module table of modules.toml: name -> {"sources", "tests", "pytest"}."""
    with open(MODULES, "rb") as f:
        return tomllib.load(f)


def source_files(spec):
    """The module's files (repository-relative, sorted), from its globs."""
    files = {Path(p).relative_to(ROOT).as_posix()
             for pattern in spec["sources"] for p in glob.glob(str(ROOT / pattern))}
    return sorted(files)


def content_hash(files):
    """SHA-256 over the files' paths and contents: what the report records of each module."""
    digest = hashlib.sha256()
    for name in files:
        digest.update(name.encode() + b"\0" + (ROOT / name).read_bytes() + b"\0")
    return digest.hexdigest()


def _scratch(name, spec, fresh):
    """Lay out _build/mutation/<name>/: the package as `mechnum/`, the tests, mutmut's config."""
    where = SCRATCH / name
    if fresh and where.exists():
        shutil.rmtree(where)
    (where / "mutants").mkdir(parents=True, exist_ok=True)
    # copy2 keeps the modification times, which mutmut compares to reuse unchanged files' mutants
    shutil.copytree(PACKAGE / "mechnum", where / "mechnum", copy_function=shutil.copy2,
                    dirs_exist_ok=True, ignore=shutil.ignore_patterns("__pycache__"))
    if not (where / "tests").exists():
        (where / "tests").symlink_to(ROOT / "tests")  # mutmut copies them into mutants/
    # the repository's data the tests read (book/, _toc.yml), next to the copied tests
    for extra in ("book", "_toc.yml"):
        link = where / "mutants" / extra
        if not link.exists():
            link.symlink_to(ROOT / extra)
    files = [f.removeprefix("pkg/") for f in source_files(spec)]
    tests = [t for pattern in spec["tests"] for t in sorted(glob.glob(pattern, root_dir=ROOT))]
    lines = ["[mutmut]", "source_paths = mechnum",
             "only_mutate =", *[f"    {f}" for f in files],
             "pytest_add_cli_args_test_selection =", *[f"    {t}" for t in tests + files],
             # doctests too; no pytest-xdist, cache or benchmark plugins inside a mutant's run
             "pytest_add_cli_args =",
             # and numpy's overflow and invalid-value warnings are errors, as in `make explore`: a
             # mutant that leaks one is killed
             *[f"    {a}" for a in ["--doctest-modules", "-p", "no:xdist", "-p", "no:cacheprovider",
                                    "-p", "no:benchmark", "-W", "error::RuntimeWarning",
                                    *spec.get("pytest", [])]],
             # a mutant whose tests take 5 times as long as the clean run's has made a loop longer:
             # killed by its timeout
             "timeout_multiplier = 5.0", "timeout_constant = 5.0",
             "use_git_change_detection = false", ""]
    (where / "setup.cfg").write_text("\n".join(lines))
    return where


def _mutmut(where, args):
    env = dict(os.environ, HYPOTHESIS_PROFILE="repeatable", MPLBACKEND="Agg",
               PYTHONDONTWRITEBYTECODE="1")
    mutmut = Path(sys.executable).with_name("mutmut")
    return subprocess.run([str(mutmut), *args], cwd=where, env=env, check=False)


def _outcomes(where, files):
    """mutant name -> status, from mutmut's per-file records."""
    outcomes = {}
    for name in files:
        meta = where / "mutants" / (name.removeprefix("pkg/") + ".meta")
        if not meta.exists():
            continue
        for key, code in json.loads(meta.read_text())["exit_code_by_key"].items():
            outcomes[key] = STATUS.get(code, f"exit {code}")
    return outcomes


def _diff(where, mutant):
    out = subprocess.run([str(Path(sys.executable).with_name("mutmut")), "show", mutant],
                         cwd=where, capture_output=True, text=True, check=True).stdout
    return out


def changed_lines(diff):
    """The removed and added lines of a mutant's diff, stripped: how equivalents.toml names it."""
    body = [line for line in diff.splitlines()[1:]
            if line[:1] in "+-" and not line.startswith(("---", "+++"))]
    return ([line[1:].strip() for line in body if line[0] == "-"],
            [line[1:].strip() for line in body if line[0] == "+"])


def _source_of(mutant):
    """The repository file of a mutant (`mechnum.newton.core.x_f__mutmut_1` -> pkg/.../core.py)."""
    dotted = mutant.partition("__mutmut_")[0].rpartition(".")[0]
    for candidate in (f"pkg/{dotted.replace('.', '/')}.py",
                      f"pkg/{dotted.replace('.', '/')}/__init__.py"):
        if (ROOT / candidate).exists():
            return ROOT / candidate
    raise FileNotFoundError(f"no source for {mutant}")


def _message_lines(path, function):
    """The stripped source lines of `function` in `path` that lie inside the message of a raise
    or of a warnings.warn call: text a reader sees, which no result depends on. (The names handed
    to the checks of mechnum._validate are not: a test that matches "n_starts must" tells
    "XXn_startsXX must" from them.)"""
    tree = ast.parse(path.read_text())
    lines = path.read_text().splitlines()
    cls, _, name = function.rpartition(".")
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef) and cls and node.name != cls:
            continue
        for fn in ast.walk(node):
            if not (isinstance(fn, ast.FunctionDef) and fn.name == name):
                continue
            for inner in ast.walk(fn):
                texts = []
                if isinstance(inner, ast.Raise) and isinstance(inner.exc, ast.Call):
                    texts = inner.exc.args[:1]
                elif isinstance(inner, ast.Call) and getattr(inner.func, "attr", getattr(
                        inner.func, "id", None)) == "warn":
                    texts = inner.args[:1]
                for text in texts:
                    found |= {lines[i - 1].strip()
                              for i in range(text.lineno, text.end_lineno + 1)}
    return found


def _strings(line):
    """The line's tokens: (non-string tokens, string tokens)."""
    tokens = []
    try:  # a line of a statement that continues on the next one ends in a TokenError
        for token in tokenize.generate_tokens(StringIO(line + "\n").readline):
            if token.type not in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER):
                tokens.append(token)
    except tokenize.TokenError:
        pass
    strings = [t.string for t in tokens if t.type == tokenize.STRING]
    return [t.string for t in tokens if t.type != tokenize.STRING], strings


def message_text_only(mutant, diff):
    """Whether a mutant only rewrites the text of an error or warning message (wrapped in XX, or
    its case changed): the message still names the problem in its words, and no value changes."""
    removed, added = changed_lines(diff)
    if len(removed) != 1 or len(added) != 1:
        return False
    try:
        (code_a, strings_a), (code_b, strings_b) = _strings(removed[0]), _strings(added[0])
    except (IndentationError, SyntaxError):
        return False
    if code_a != code_b or len(strings_a) != len(strings_b) or strings_a == strings_b:
        return False
    for a, b in zip(strings_a, strings_b):
        if a != b and a.lower() != b.lower() and b.replace("XX", "", 2) != a:
            return False
    return removed[0] in _message_lines(_source_of(mutant), function_of(mutant))


def function_of(mutant):
    """`mechnum.newton.core.x_solve__mutmut_3` -> `solve` (a method: `Class.method`)."""
    mangled = mutant.rpartition(".")[2].partition("__mutmut_")[0]
    if "ǁ" in mangled:
        _, cls, method = mangled.split("ǁ")
        return f"{cls}.{method}"
    return mangled.removeprefix("x_")


def run(names, retry=False):
    table = modules()
    results = json.loads(RESULTS.read_text()) if RESULTS.exists() else {}
    for name in names:
        spec = table[name]
        files = source_files(spec)
        mutated = content_hash(files)  # what is copied now is what the report will cover
        where = _scratch(name, spec, fresh=not retry)
        start = time.monotonic()
        # mutmut keeps the results of the functions that did not change; a retry then runs the
        # survivors again (against the tests as they are now)
        _mutmut(where, ["run"])
        if retry:
            survivors = [m for m, s in _outcomes(where, files).items() if s == SURVIVED]
            if survivors:
                _mutmut(where, ["run", *survivors])
        seconds = time.monotonic() - start
        outcomes = _outcomes(where, files)
        survivors = {m: _diff(where, m) for m, s in sorted(outcomes.items()) if s == SURVIVED}
        previous = results.get(name, {})
        results[name] = {
            "files": files, "sha256": mutated,
            "counts": {s: sum(v == s for v in outcomes.values())
                       for s in sorted(set(outcomes.values()))},
            "survivors": [{"mutant": m, "function": function_of(m), "diff": d,
                           "message_text": message_text_only(m, d)}
                          for m, d in survivors.items()],
            # a retry reruns the survivors only: the full run's time is the one to quote
            "seconds": previous.get("seconds", round(seconds)) if retry else round(seconds),
        }
        RESULTS.write_text(json.dumps(results, indent=1, sort_keys=True) + "\n")
    report()


def equivalents():
    """equivalents.toml: the rule for message text, and the mutants argued equivalent one by one,
    each with its reason."""
    with open(EQUIVALENTS, "rb") as f:
        return tomllib.load(f)


def classify(name, entry, known):
    """Split a module's survivors into equivalent (a message's text only, or matched by an entry
    of equivalents.toml: same module, function and changed lines) and the rest, each equivalent
    one with its reason."""
    equivalent, alive = [], []
    for survivor in entry["survivors"]:
        removed, added = changed_lines(survivor["diff"])
        match = [e["reason"] for e in known.get("equivalent", [])
                 if e["module"] == name and e["function"] == survivor["function"]
                 and e["removed"] == removed and e["added"] == added]
        if not match and survivor["message_text"]:
            match = [known["message_text"]["reason"]]
        (equivalent if match else alive).append((survivor, match[0] if match else None))
    return equivalent, alive


def score(entry, n_equivalent):
    counts = entry["counts"]
    killed = counts.get(KILLED, 0)
    total = sum(counts.values())
    return killed, total, killed / max(total - n_equivalent, 1)


def report():
    """Write bench/mutation.md."""
    REPORT.write_text(render())


def render():
    """bench/mutation.md's text, from results.json and equivalents.toml."""
    results = json.loads(RESULTS.read_text())
    known = equivalents()
    table = modules()
    out = ["# Mutation testing of the methods layer",
           "",
           "Written by `make mutate` (`bench/mutation/mutate.py`) from mutmut's results; do not "
           "edit by hand. Each module (`bench/mutation/modules.toml`) is mutated alone and every "
           "mutant is run against the module's own tests and doctests. A mutant is *killed* when "
           "a test fails (or it runs out of time), *equivalent* when it cannot change any result "
           "(listed below with the reason, from `bench/mutation/equivalents.toml`), *survived* "
           "otherwise. mutmut mutates the bodies of functions and methods, not module constants "
           "nor decorated functions (the numba kernels).",
           "",
           "| module | mutants | killed | equivalent | survived | no tests | killed / "
           "(mutants - equivalent) | minutes |",
           "|---|---:|---:|---:|---:|---:|---:|---:|"]
    details = []
    for name in table:
        if name not in results:
            out.append(f"| {name} | not run | | | | | | |")
            continue
        entry = results[name]
        equivalent, alive = classify(name, entry, known)
        killed, total, rate = score(entry, len(equivalent))
        out.append(f"| {name} | {total} | {killed} | {len(equivalent)} | {len(alive)} | "
                   f"{entry['counts'].get(NO_TESTS, 0)} | {100 * rate:.1f} % | "
                   f"{entry['seconds'] / 60:.0f} |")
        if equivalent or alive:
            details.append(f"\n## {name}\n")
        for survivor, why in equivalent:
            details.append(f"- equivalent, `{survivor['function']}`: {why}\n")
            details.append("  ```diff\n" + _indent(survivor["diff"]) + "\n  ```")
        for survivor, _ in alive:
            details.append(f"- **survived**, `{survivor['function']}` ({survivor['mutant']})\n")
            details.append("  ```diff\n" + _indent(survivor["diff"]) + "\n  ```")
    out += ["", "Each module's files and their SHA-256 (`bench/mutation/test_report.py` checks "
            "them against the files as they are):", ""]
    for name in table:
        if name in results:
            out.append(f"- {name}: `{results[name]['sha256'][:16]}` "
                       f"({', '.join(results[name]['files'])})")
    return "\n".join(out + details) + "\n"


def _indent(diff):
    lines = [line for line in diff.splitlines() if not line.startswith(("---", "+++", "# "))]
    return "\n".join("  " + line for line in lines)


def survivors(name):
    results = json.loads(RESULTS.read_text())
    _, alive = classify(name, results[name], equivalents())
    for survivor, _ in alive:
        print(f"# {survivor['mutant']}\n{survivor['diff']}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("action", choices=["run", "retry", "report", "survivors"])
    parser.add_argument("modules", nargs="*")
    args = parser.parse_args()
    table = modules()
    unknown = set(args.modules) - set(table)
    if unknown:
        parser.error(f"unknown modules {sorted(unknown)}; modules.toml has {list(table)}")
    if args.action == "run":
        run(args.modules or list(table))
    elif args.action == "retry":
        run(args.modules, retry=True)
    elif args.action == "report":
        report()
    else:
        for name in args.modules:
            survivors(name)


if __name__ == "__main__":
    main()
