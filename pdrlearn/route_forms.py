"""Decision S91: every item kind ``--route`` accepts, with its form - the one table the parser
(:func:`pdrlearn.sim.route.parse_route`, its ``ROUTE_KINDS``) and ``simulate --route``'s help are built from, so the
help lists every kind. No imports: ``import pdrlearn.cli`` stays light (tests/test_cli_import_light.py)."""

#: decision S91: kind -> its form and meaning, in the help's order (the parser accepts exactly these kinds)
ROUTE_FORMS = {
    "straight": "'straight:M[:GAIT][:PACE]' M metres ahead, GAIT short / normal / long, PACE slow / normal / fast "
                "(this walk's own speed, 'straight:14:fast'; S88)",
    "curve": "'curve:DEG:R[:GAIT]' an arc of DEG degrees (+ left) of radius R m",
    "slope": "'slope:M:PCT' (or 'slope:M:PCT:GAIT') M metres (horizontal) on a ramp of PCT % (-30 to 30, < 0 downhill; "
             "'slope:9:8.33' is a 1:12 ramp; S37)",
    "up": "'up:N[:RISE:RUN][:step-to-step][:PACE]' N stairs up (default 0.17 m rise x 0.28 m run; step-to-step: "
          "both feet on each stair, S80; 'step-to-step:left' / ':right': that foot leads every stair, S92; last, "
          "the flight's pace: slow / normal / fast or 'pace=F', each stair step F x the level step time, "
          "'up:12:pace=1.5'; S101)",
    "down": "'down:N[:RISE:RUN][:step-to-step][:PACE]' N stairs down",
    "backward": "'backward:N[:direct]' N backward steps (0.5: half a step, S89; direct: reversing straight out of "
                "forward walking, no stop, S67)",
    "turn": "'turn:DEG' turning in place by stepping (+ left; S9)",
    "pivot": "'pivot:DEG[:N[:STEP]]' turning on the spot without stopping, in N short steps (0, the default: one "
             "per few degrees) each moving the body STEP m (default 0.15; S41)",
    "spin": "'spin:DEG:S' stopping and turning DEG degrees (+ left) on the spot in S seconds (1-120) without a step: "
            "the body spins on the tracked foot, which stays planted (spins.csv; S106)",
    "inplace": "'inplace:N' N steps on the spot, marking time (no turn, no travel; S105)",
    "stand": "'stand:S' standing S seconds",
    "sit": "'sit:S' sitting down, seated S seconds, standing up (a chair; transfers.csv)",
    "lift": "'lift:+M' / 'lift:-M' a lift M metres up / down, no steps ('lift:+9': three storeys; S45)",
    "escalator": "'escalator:+M' / 'escalator:-M' 30 deg, 0.5 m/s, straight ahead (1-60 m; 'escalator:+6', "
                 "'escalator:-9'; S45)",
    "trolley": "'trolley:M[:GAIT]' M metres pushing a trolley ('trolley:20'; S46): a free walk with the pelvic "
               "rotation and trunk yaw halved; a walking aid (rollator, cane) is not simulated (W456)",
    "side": "'side:M' side-stepping M metres left (-M right) facing ahead (S49)",
    "freeze": "'freeze:S[:HZ[:ACC]]' a freezing-of-gait episode: trembling in place S seconds (S51)",
    "lie": "'lie:S[:ROLLS]' sits on a bed edge, lies down S seconds turning over ROLLS times an hour (default 2; 0 "
           "never), sits up and stands up ('lie:28800': a night; lying.csv, rolls.csv; up to 86400 s; S58-S61)",
    "vehicle": "'vehicle:S[:RMS[:RISE]]' standing S seconds in a moving vehicle, no steps (RMS its vibration, "
               "drawn when empty; RISE m climbed; S71, S75)",
    "cycle": "'cycle:S' getting on a bicycle, pedalling seated S seconds (20-3600) and getting off, no steps (the "
             "foot round the crank; rides.csv kind cycle; S99)",
}


def route_help() -> str:
    """Decision S91: ``simulate --route``'s help, every kind of :data:`ROUTE_FORMS` listed. ``[i][/i]`` after each
    ':' keeps rich from reading ':M:' as an emoji code (S56)."""
    items = "; ".join(ROUTE_FORMS.values())
    return ("Your own path instead of a scenario, items separated by commas, e.g. 'straight:10, up:12, turn:180, "
            "down:12, backward:3, stand:2, curve:90:2' (degrees; docs/simulator.md). Every item: "
            + items + ".").replace(":", ":[i][/i]")
