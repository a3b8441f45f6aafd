"""Shared fixtures: each kit is built once per test session."""

from pathlib import Path

import pytest

from partgen import pipeline

ROOT = Path(__file__).parent.parent
CONFIGS = ROOT / "configs"


@pytest.fixture(scope="session")
def built_kits(tmp_path_factory):
    """name -> (Loaded, Kit, manifest dict, kit folder) for the two butterfly designs."""
    out = {}
    for name in ("butterfly", "butterfly_liu2017"):
        dest = tmp_path_factory.mktemp("kits") / name
        out[name] = pipeline.build(CONFIGS / f"{name}.yaml", dest)
    return out


@pytest.fixture(scope="session")
def shipped_kits(tmp_path_factory):
    """name -> (Loaded, Kit, manifest dict, kit folder) for every shipped config (configs/*.yaml)."""
    out = {}
    for cfg in sorted(CONFIGS.glob("*.yaml")):
        dest = tmp_path_factory.mktemp("shipped") / cfg.stem
        out[cfg.stem] = pipeline.build(cfg, dest)
    return out
