"""riser's API pages by rustdoc on the tests' build (`make doc`): no check of the dependencies.

`cargo doc` documents a crate against its dependencies' metadata from a *check* (cargo's units
in check mode), never from a build, so after `make test-build` it still checked every dependency
again (about 90 s of CPU on a fresh clone). This calls rustdoc on src/lib.rs as `cargo doc`
would, but with the rlibs of the build as its `--extern`s:

* the build's artifacts from `cargo build --all-targets --message-format=json` (the same target
  selection as `make test-build`, so nothing is built again, and the dependencies' features are
  the build's), the build script's OUT_DIR (src/fmi/vars.rs includes files written there);
* the library's direct dependencies from Cargo.toml's [dependencies] (riser has no
  platform-specific ones), each matched to the one library of that package the build made.

Standard library only (it runs before the venv is needed): `python3 rustdoc.py --profile fasttest
-- -D warnings`. Arguments after `--` go to rustdoc; `-D warnings` makes a broken intra-doc link
an error, as RUSTDOCFLAGS="-D warnings" did for `cargo doc`. The pages: target/doc/riser/.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path


def cargo_json(cargo: str, args: list[str], cwd: Path) -> list[dict]:
    p = subprocess.run([cargo, *args], cwd=cwd, stdout=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit(f"rustdoc.py: `cargo {' '.join(args)}` failed ({p.returncode})")
    return [json.loads(line) for line in p.stdout.splitlines() if line.startswith("{")]


def rustdoc_command(root: Path, profile: str, cargo: str, rustdoc: str, out: Path | None,
                    extra: list[str]) -> tuple[list[str], dict[str, str]]:
    """The rustdoc command line and environment of riser's library, from the build's artifacts."""
    messages = cargo_json(cargo, ["build", "--profile", profile, "--all-targets",
                                  "--message-format=json-render-diagnostics"], root)
    manifest = tomllib.loads((root / "Cargo.toml").read_text())
    package = manifest["package"]

    def package_name(package_id: str) -> str:  # "registry+...#toml@1.2.1", "path+file:///dir#riser@0.1.0"
        return package_id.rsplit("#", 1)[1].split("@")[0]

    # the library files of each package as built (not test harnesses), and the library's own unit
    built: dict[str, list[dict]] = {}
    me = None
    for m in messages:
        if m["reason"] == "compiler-artifact" and not m["profile"]["test"] and \
                set(m["target"]["kind"]) & {"lib", "rlib", "proc-macro"}:
            if Path(m["manifest_path"]) == root / "Cargo.toml":
                me = m
            else:
                built.setdefault(package_name(m["package_id"]), []).append(m)
    if me is None:
        sys.exit("rustdoc.py: the library is not among cargo's artifacts")
    out_dir = next((m["out_dir"] for m in messages
                    if m["reason"] == "build-script-executed" and m["package_id"] == me["package_id"]), None)
    if out_dir is None:
        sys.exit("rustdoc.py: the build script's OUT_DIR is not in cargo's messages")

    # the normal dependencies of Cargo.toml (not dev-, not build-), as the library's `--extern`s
    externs = []
    for key, spec in manifest.get("dependencies", {}).items():
        name = spec.get("package", key) if isinstance(spec, dict) else key
        arts = {tuple(a["filenames"]): a for a in built.get(name, [])}
        if len(arts) != 1:
            sys.exit(f"rustdoc.py: dependency {name}: expected one library built, found {len(arts)}")
        a = next(iter(arts.values()))
        files = [f for f in a["filenames"] if f.endswith(".rlib")] or [f for f in a["filenames"] if f.endswith(".so")]
        crate = key if isinstance(spec, dict) and "package" in spec else a["target"]["name"]
        externs += ["--extern", f"{crate.replace('-', '_')}={files[0]}"]
    lib = me["target"]

    deps_dir = Path(externs[1].split("=", 1)[1]).parent  # target/PROFILE/deps (or CARGO_TARGET_DIR's)
    out = out or deps_dir.parent.parent / "doc"
    # the source path relative to the package, as cargo gives it (the source pages name it)
    cmd = [rustdoc, f"--edition={lib['edition']}", "--crate-type", "lib", "--crate-name",
           lib["name"].replace("-", "_"), os.path.relpath(lib["src_path"], root), "-o", str(out),
           "-L", f"dependency={deps_dir}", *externs, "--crate-version", package["version"],
           "--check-cfg", "cfg(docsrs,test)", "--check-cfg", "cfg(feature, values())"]
    # the [lints] of Cargo.toml that rustdoc reads (cargo passes them as cargo doc does)
    for tool, table in manifest.get("lints", {}).items():
        if tool in ("rust", "rustdoc"):
            for name, level in table.items():
                level = level["level"] if isinstance(level, dict) else level
                cmd.append(f"--{level}={'' if tool == 'rust' else 'rustdoc::'}{name}")
    cmd += extra
    env = dict(os.environ, OUT_DIR=out_dir, CARGO_PKG_NAME=package["name"], CARGO_PKG_VERSION=package["version"],
               CARGO_MANIFEST_DIR=str(root), CARGO_CRATE_NAME=lib["name"].replace("-", "_"))
    return cmd, env


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--profile", default="fasttest")
    ap.add_argument("--out", default=None, help="the pages' directory (default: the target directory's doc/)")
    ap.add_argument("--root", default=None, help="the repository (default: the one this file is in)")
    ap.add_argument("-v", "--verbose", action="store_true", help="print the rustdoc command")
    ap.add_argument("rustdoc_args", nargs="*", help="after --: rustdoc's own (e.g. -D warnings)")
    a = ap.parse_args(argv)
    root = Path(a.root).resolve() if a.root else Path(__file__).resolve().parents[4]
    out = Path(a.out).resolve() if a.out else None
    cmd, env = rustdoc_command(root, a.profile, os.environ.get("CARGO", "cargo"), os.environ.get("RUSTDOC", "rustdoc"),
                               out, a.rustdoc_args)
    if a.verbose:
        print(" ".join(cmd), file=sys.stderr)
    return subprocess.run(cmd, cwd=root, env=env).returncode


if __name__ == "__main__":
    sys.exit(main())
