"""Datasets others can load: performed runs and the shipped demonstrations as plain JSON lines
(:func:`~l2p_bullet.export.episodes.write_jsonl`, the default) or a LeRobot v3.0 dataset
(:func:`~l2p_bullet.export.lerobot.write_lerobot`: Parquet + MP4, written with pyarrow)."""
