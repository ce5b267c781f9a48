"""Snakemake adapter: a page the report shows inline. A GIF animation becomes an image in a page, the
validation report (Markdown) an HTML table; the report offers either only for download as it is."""

import base64
import html
from pathlib import Path

import markdown
from _log import logged

from dccss.files import write_text

STYLE = ("body{font-family:sans-serif;font-size:13px;margin:0} img{max-width:100%}"
         " table{border-collapse:collapse} th,td{border:1px solid #ccc;padding:2px 5px;vertical-align:top}")

with logged(snakemake.log[0]):
    source = Path(snakemake.input[0])
    if source.suffix == ".gif":
        data = base64.b64encode(source.read_bytes()).decode("ascii")
        body = f'<img alt="{html.escape(source.name)}" src="data:image/gif;base64,{data}">'
    else:
        body = markdown.markdown(source.read_text(encoding="utf-8"), extensions=["tables"])
    write_text(f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{html.escape(source.name)}</title>"
               f"<style>{STYLE}</style></head>\n<body>\n{body}\n</body></html>\n", snakemake.output[0])
    print(f"wrote {snakemake.output[0]} from {source}")
