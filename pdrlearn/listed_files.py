"""Decisions E263 / E269: a file a folder's manifest lists is the folder's own only when its entry stays in the
folder and the file lies inside the folder once its links are followed. One check for the runtime bundles (E263,
``runtime.bundle.verify_files``) and the model folders ``train`` writes (E269,
``classify.model_dir.verify_model_dir``). Standard library only: the lean runtime imports it."""

from __future__ import annotations

from pathlib import Path


def climbs_out(rel: str) -> bool:
    """The manifest entry ``rel`` is absolute or climbs out with ``..``: no file of the folder (a forged manifest)."""
    return Path(rel).is_absolute() or ".." in Path(rel).parts


def linked_outside(folder: Path, rel: str) -> Path | None:
    """Decision E263: where the listed file ``rel`` of ``folder`` resolves when a symbolic link (the file's, or a
    linked folder on its way) takes it outside the resolved folder; None when it is the folder's own. A link that
    stays inside is allowed: the bytes are the folder's."""
    target = (folder / rel).resolve()
    return None if target.is_relative_to(folder.resolve()) else target


def linked_message(rel: str, target: Path, kind: str) -> str:
    """The one line's text for :func:`linked_outside`'s finding; ``kind``: "bundle" or "model" (folder)."""
    return (f"file '{rel}' is a symbolic link (or inside a linked folder) to {target}, outside the {kind}; copy the "
            f"whole {kind} folder with its files (cp -rL), not links")
