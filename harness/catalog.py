"""Discovers studies (studies/<name>/study.yaml) and loads their reference files."""
import os

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
