"""Discovers studies (studies/<name>/study.yaml) and loads their reference files."""
import hashlib
import os
import subprocess

import yaml

from . import HarnessError

STUDY_FIELDS = ("name", "chapter", "title", "reproduces", "description")


def load_yaml(path, what):
    if not os.path.isfile(path):
        raise HarnessError(f"{what}: file {path} does not exist")
    try:
        with open(path) as f:
            doc = yaml.safe_load(f)
    except yaml.YAMLError as e:
        line = getattr(getattr(e, "problem_mark", None), "line", None)
        where = f" (line {line + 1})" if line is not None else ""
        raise HarnessError(f"{what}: {path} is not valid YAML{where}: {getattr(e, 'problem', e)}")
    if not isinstance(doc, dict):
        raise HarnessError(f"{what}: {path} must hold a mapping, found {type(doc).__name__}")
    return doc


def studies(root):
    """All studies by name, each its study.yaml mapping plus 'dir'."""
    base = os.path.join(root, "studies")
    found = {}
    for name in sorted(os.listdir(base)):
        meta_path = os.path.join(base, name, "study.yaml")
        if not os.path.isfile(meta_path):
            continue
        meta = load_yaml(meta_path, f"study '{name}'")
        for field in STUDY_FIELDS:
            if field not in meta:
                raise HarnessError(f"study '{name}': {meta_path} lacks the field '{field}'")
        if meta["name"] != name:
            raise HarnessError(f"study '{name}': {meta_path} has name '{meta['name']}', expected '{name}'")
        meta["dir"] = os.path.join(base, name)
        found[name] = meta
    return found


def select(root, target):
    """Studies named by target: a study name, a chapter name, or 'all'."""
    every = studies(root)
    if target == "all":
        return list(every.values())
    if target in every:
        return [every[target]]
    chapter = [m for m in every.values() if m["chapter"] == target]
    if chapter:
        return chapter
    names = ", ".join(sorted(set(every) | {m["chapter"] for m in every.values()}))
    raise HarnessError(f"unknown study or chapter '{target}' (known: all, {names})")


CHECK_KINDS = {"value", "order", "bound"}


def reference(root, name):
    """reference/<name>.yaml, validated."""
    path = os.path.join(root, "reference", f"{name}.yaml")
    ref = load_yaml(path, f"reference for '{name}'")
    for field in ("study", "source", "checks"):
        if field not in ref:
            raise HarnessError(f"reference {path}: missing field '{field}'")
    if ref["study"] != name:
        raise HarnessError(f"reference {path}: study is '{ref['study']}', expected '{name}'")
    if not isinstance(ref["checks"], list) or not ref["checks"]:
        raise HarnessError(f"reference {path}: 'checks' must be a non-empty list")
    seen = set()
    for i, c in enumerate(ref["checks"]):
        if not isinstance(c, dict):
            raise HarnessError(f"reference {path}: checks[{i}] must be a mapping")
        cid = c.get("id", f"checks[{i}]")
        for field in ("id", "kind", "source"):
            if field not in c:
                raise HarnessError(f"reference {path}: check '{cid}' lacks the field '{field}'")
        if c["kind"] not in CHECK_KINDS:
            raise HarnessError(f"reference {path}: check '{cid}' has kind '{c['kind']}', not one of {sorted(CHECK_KINDS)}")
        if "when" in c:
            raise HarnessError(f"reference {path}: check '{cid}' has 'when', which is now 'run: <id>' "
                               "(the run it measures, from the results' runs)")
        run = c.get("run")
        ids = lambda r: isinstance(r, str) or (isinstance(r, list) and r and all(isinstance(x, str) for x in r))  # noqa: E731
        if run is not None and not (ids(run) or (isinstance(run, dict) and run and set(run) <= {"quick", "full"}
                                                 and all(ids(v) for v in run.values()))):
            raise HarnessError(f"reference {path}: check '{cid}' has run = {run!r}; expected a run id, a list of them, "
                               "or a mapping from scale (quick, full) to either")
        if not isinstance(c.get("speed", False), bool):
            raise HarnessError(f"reference {path}: check '{cid}' has speed = {c['speed']!r}; expected true or false")
        if cid in seen:
            raise HarnessError(f"reference {path}: check id '{cid}' appears twice")
        seen.add(cid)
    figures = ref.get("figures", []) or []
    for i, fig in enumerate(figures):
        for field in ("id", "table", "x", "y"):
            if field not in fig:
                raise HarnessError(f"reference {path}: figures[{i}] lacks the field '{field}'")
    if not any(f.get("id") == "speed_vs_error" for f in figures):
        raise HarnessError(f"reference {path}: no figure 'speed_vs_error' (every study reports wall time against error)")
    return ref


def _digest(files):
    """sha256 over (relative path, content) pairs, in path order; the first 12 hex digits."""
    h = hashlib.sha256()
    for rel, data in sorted(files):
        h.update(rel.encode() + b"\0" + data + b"\0")
    return h.hexdigest()[:12]


def _read(root, rel):
    with open(os.path.join(root, rel), "rb") as f:
        return f.read()


def source_files(root, name):
    """The files whose change makes a study's report stale: its driver's folder studies/<name>/
    and its reference file. Paths relative to root."""
    out = [os.path.join("reference", f"{name}.yaml")]
    base = os.path.join(root, "studies", name)
    for d, _, files in os.walk(base):
        out += [os.path.relpath(os.path.join(d, f), root) for f in files]
    return out


def driver_hash(root, name):
    """Hash of the driver's sources (studies/<name>/) as they are in the tree now."""
    files = [p for p in source_files(root, name) if p.startswith("studies")]
    return _digest((p, _read(root, p)) for p in files)


def reference_hash(root, name):
    p = os.path.join("reference", f"{name}.yaml")
    return _digest([(p, _read(root, p))])


def driver_hash_at(root, name, commit):
    """The same hash for the sources at a git commit (for reports that recorded only their commit);
    None when git or the commit is not available, or the commit had uncommitted changes."""
    if not commit or commit == "unknown" or "+" in commit:
        return None
    try:
        ls = subprocess.run(["git", "-C", root, "ls-tree", "-r", "--name-only", commit, f"studies/{name}/"],
                            capture_output=True, timeout=20)
        if ls.returncode != 0:
            return None
        files = []
        for p in ls.stdout.decode().split():
            blob = subprocess.run(["git", "-C", root, "show", f"{commit}:{p}"], capture_output=True, timeout=20)
            if blob.returncode != 0:
                return None
            files.append((p, blob.stdout))
        return _digest(files) if files else None
    except (OSError, subprocess.SubprocessError):
        return None
