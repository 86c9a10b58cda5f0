"""The shipped data and its readers, on a low floor every other subpackage may import.

- ``demos``: the people's motion-capture demonstrations (``captures/``) and the study's graded 2-D
  demonstrations (``sim/``), read into plain arrays; ``tracking`` cleans capture glitches on the way in.
- ``grades``: people's grades of runs (the review app's export and database), read and written as
  :class:`~l2p_bullet.data.grades.GradeRow` rows; ``review_schema`` is that database's schema.
The review app (``review/``), the learners (``learning/``), replay and teach all read through here, so
none of them has to import another's room. Torch-free and web-free.
"""
