"""What the peers of bench/peer/ transcribe of a task, and what they refuse (shared by the IPOPT and Moco peers)."""


def unsupported_features(task):
    """The features of a resolved task (task.resolved.toml, parsed) that the peers do not transcribe: contacts,
    balance, external forces, the H^-1 objective, a via/CSV guess, free end velocities, other end conditions,
    frame goals. Returns their names; empty when the task is one the peers solve as mintorque does."""
    c = task.get("constraints", {})
    env = task.get("environment", {})
    motion = task.get("motion", {})
    unsupported = []
    if c.get("contact"):
        unsupported.append("constraints.contact")
    if c.get("balance"):
        unsupported.append("constraints.balance")
    if env.get("force"):
        unsupported.append("environment.force")
    if task.get("objective", {}).get("kind", "torque") != "torque":
        unsupported.append("objective.kind")
    guess = task.get("discretization", {}).get("initial_guess", "linear")
    if guess != "linear":
        unsupported.append(f"discretization.initial_guess = {guess!r}")
    if not motion.get("zero_end_velocity", True):
        unsupported.append("motion.zero_end_velocity = false")
    for end in ("start_condition", "goal_condition"):
        if motion.get(end, "rest") != "rest":
            unsupported.append(f"motion.{end}")
    if motion.get("frame_goal"):
        unsupported.append("motion.frame_goal")
    return unsupported
