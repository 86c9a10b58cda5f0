"""Built-in composite action bundle: row ("make a row of A, B, C and D"); manifest.toml, recipe.json and the
demonstrations it was learned from (demos.json, recorded on the teach page by tests/teach/test_teach_rows_browser.py).
"""
