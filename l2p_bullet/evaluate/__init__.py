"""Research at scale: ``l2p-bullet evaluate`` runs every scene x action on a process pool or Ray.

    scenes   scene sets: seeded random, a JSON-lines file, the original study's starts, bystanders
    tasks    one run of one action on one scene, as plain data
    worker   perform/plan a task, judge it by every installed action (the confusion matrix), return a row
    pool     the local backend: W processes kept for the whole evaluation, crash-tolerant
    ray_backend  the same tasks on Ray actors (optional extra l2p-bullet[ray])
    results  the results table (SQLite, one committed row per run)
    folder   the evaluation folder: what evaluate writes there, and the checks made before it writes
    runner   evaluate(config, out): build, skip what is recorded, run, record
    confusion, report   success per action, the judge- and model-based confusion matrices, PNGs

Nothing heavy is imported here: the CLI's ``--help`` stays fast.
"""
