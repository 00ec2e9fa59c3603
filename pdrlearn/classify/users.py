"""Who a model and a session belong to (decisions C29, C138, C152, C227): the light part of
:mod:`pdrlearn.classify.training` (numpy and the cohort helpers only, no scikit-learn), so ``pdrlearn run`` can
name a per-user model's own user without importing the training stack (decision E262's import rule)."""

from __future__ import annotations

#: how :func:`pdrlearn.cohort.meta_user_key` names a user: a model's ``data_summary["users"]`` entry of another form
#: is a given name (``--user P001``, decision E174)
_USER_KEY_PREFIXES = ("user:", "user.", "subject:", "subject.")


def model_user_key(model) -> str | None:
    """Decisions C138, C152: the one user a per-user model was fitted on, as its ``data_summary["users"]`` names it:
    :func:`session_user`'s key (``user.seed:9460``) or a name given at training (``P001``, decision E174); None when
    it names none or several (a pooled model: a new user is its intended use)."""
    users = (getattr(model, "data_summary", None) or {}).get("users") or []
    return users[0] if len(users) == 1 and isinstance(users[0], str) and users[0].strip() else None


def own_user(model, sessions) -> str | None:
    """Decision C227: the per-user model's user (:func:`model_user_key`) when every one of ``sessions`` (one or a
    list) names that user in its meta.json (C138 / C152's match, :func:`other_user_line`); None for a pooled model,
    a session of another user or of no named user (then C16's advice to train a per-user model stands)."""
    key = model_user_key(model)
    sessions = sessions if isinstance(sessions, list | tuple) else [sessions]
    if key is None or not sessions:
        return None
    return key if all(key in (session_user(s), _one_user(s)) for s in sessions) else None


def bundle_own_user(bundle, session) -> str | None:
    """Decision C227: :func:`own_user` for a runtime bundle (its manifest's ``training.data``, the model's
    ``data_summary`` it was exported from) and the replayed ``session``."""
    from types import SimpleNamespace

    data = ((getattr(bundle, "manifest", None) or {}).get("training") or {}).get("data") or {}
    return own_user(SimpleNamespace(data_summary=data), session)


def session_user(session) -> str | None:
    """The user a session was recorded from, from its ``meta.json`` (decision C29): ``user`` (a string, or an
    object with ``id`` or ``seed``, as the simulator writes) or ``subject`` (a string, or an object with ``id``
    or ``participant_id``, as the mobgap converter writes); ``None`` when the session names none
    (:func:`pdrlearn.cohort.meta_user_key`, which track-all's changes.csv reads too, cohort C22)."""
    from pdrlearn.cohort import meta_user_key

    return meta_user_key(getattr(session, "meta", None) or {}, getattr(session, "folder", None))


def _one_user(session) -> str | None:
    """The name of a one-user model (decisions B88, C48): the session's ``user``/``subject`` text as written
    (``anna``), else :func:`session_user`'s name of an object (``user.seed:3`` for a simulated session, not the
    object itself); None when it names none (:func:`pdrlearn.cohort.meta_user`, track-all's subject, C22)."""
    from pdrlearn.cohort import meta_user

    return meta_user(getattr(session, "meta", None) or {}, getattr(session, "folder", None))
