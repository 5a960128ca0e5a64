"""The report as a reader sees it: `snakemake --report` of the quick run, opened in headless
Chromium, lists every figure and table the run made, each under the category its rule gives it
and with its caption.

The report is a single-page JavaScript app (the list of results exists only once the app runs),
so the page is rendered in Chromium and read the way a reader reads it: open a category from the
menu, read its table of files, open each file's information panel and read its description.
Chromium is driven over the DevTools protocol on a pipe (``--remote-debugging-pipe``: no port is
opened) and runs in a process group of its own, which the test ends when it is done.

What the report must list is derived, not written here: the ``report(...)`` outputs of
``workflow/rules/*.smk`` that the quick run made; and, so that a figure dropped from the report
(its ``report()`` wrapper removed) cannot pass unseen, every figure file the run wrote must be
listed too, and every caption in ``workflow/report/`` must belong to a ``report()`` entry."""

from __future__ import annotations

import fcntl
import json
import os
import re
import select
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import QUICK, ROOT, snakemake

# one shape of report() call, as snakefmt writes it; another shape fails report_entries loudly
REPORT_CALL = re.compile(
    r'report\(\s*"(?P<path>[^"]+)",\s*caption="(?P<caption>[^"]+)",'
    r'\s*category="(?P<category>[^"]+)",?\s*\)'
)
FIGURE_SUFFIXES = (".pdf", ".png", ".svg")


@dataclass(frozen=True)
class Entry:
    path: str  # relative to the workflow directory, as in the rule
    caption: Path
    category: str


def report_entries(root: Path = ROOT) -> list[Entry]:
    """Every ``report(...)`` output of the workflow's rules."""
    entries = []
    for smk in sorted((root / "workflow" / "rules").glob("*.smk")):
        text = smk.read_text()
        found = [
            Entry(m["path"], (smk.parent / m["caption"]).resolve(), m["category"])
            for m in REPORT_CALL.finditer(text)
        ]
        # a report() with other arguments (subcategory, labels, ...) is not skipped silently
        assert len(found) == text.count("report("), f"{smk.name}: a report() not of the form read"
        entries += found
    return entries


def workflow_caption(root: Path = ROOT) -> Path:
    """The Snakefile's own ``report:`` description (the report's front page, not an entry)."""
    m = re.search(r'^report:\s*"([^"]+)"', (root / "Snakefile").read_text(), re.M)
    assert m, "Snakefile has no report: description"
    return (root / m[1]).resolve()


def caption_text(text: str) -> str:
    """A caption as words: reStructuredText source and rendered HTML text compare equal."""
    return " ".join(re.sub(r"[`*_|]", "", text).split())


def test_every_caption_belongs_to_a_report_entry():
    captions = {p.resolve() for p in (ROOT / "workflow" / "report").glob("*.rst")}
    used = {e.caption for e in report_entries()}
    assert used <= captions, f"captions named by a rule but missing: {sorted(used - captions)}"
    orphans = captions - used - {workflow_caption()}
    assert not orphans, f"captions no report() uses (a result dropped from the report?): {orphans}"


def front_page(template: str, config: dict) -> str:
    """The report's front page as text: the ``report:`` description rendered as Snakemake's
    report renders it (Jinja with trim_blocks and lstrip_blocks, ``snakemake.config`` the run's
    config, then docutils), its HTML tags dropped; a docutils warning fails."""
    import html

    from docutils.core import publish_parts
    from jinja2 import Environment

    class Snakemake:
        pass

    Snakemake.config = config
    env = Environment(trim_blocks=True, lstrip_blocks=True)
    rst = env.from_string(template).render(snakemake=Snakemake, categories={}, files={})
    body = publish_parts(rst, writer="html", settings_overrides={"halt_level": 2})
    return html.unescape(re.sub(r"<[^>]+>", "", body["html_body"]))


def missing_config(page: str, config: dict) -> list[str]:
    """The entries of `config` that `page` does not show: a section's entries as indented
    ``name: value`` lines under its ``section:`` line, a plain value as a ``name: value`` line
    (a value as Python prints it)."""
    shown, section = set(), None
    for line in page.splitlines():
        if line.startswith("  ") and section:
            shown.add((section, line.strip()))
        else:
            section = line[:-1] if line.endswith(":") and " " not in line else None
            shown.add((None, line.strip()))
    missing = []
    for key, value in config.items():
        if isinstance(value, dict) and value:
            missing += [f"{key}.{k}" for k, v in value.items() if (key, f"{k}: {v}") not in shown]
        elif (None, f"{key}: {value}") not in shown:
            missing.append(key)
    return missing


def test_front_page_shows_the_configuration_the_run_used():
    """The front page promises "the configuration shown below": it shows every section of the
    quick run's config (config.yaml with quick.yaml merged over it) with its values, the quick
    values (N = 12) and not the full config's."""
    import yaml
    from snakemake.utils import update_config

    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    update_config(config, yaml.safe_load((ROOT / "config" / "quick.yaml").read_text()))
    page = front_page(workflow_caption().read_text(), config)
    assert "shown below" in page
    assert missing_config(page, config) == []
    # the control: a front page that shows no configuration fails the check
    assert "numerics.N" in missing_config(
        front_page("The configuration shown below.", config), config
    )


class Chromium:
    """Headless Chromium and a DevTools-protocol client on a pipe: the browser reads commands on
    its fd 3 and writes answers and events on its fd 4, each message JSON ended by a NUL."""

    def __init__(self, profile: Path, log: Path):
        exe = shutil.which("chromium") or shutil.which("chromium-browser")
        if exe is None:  # CI installs it (.ci/run): a missing browser fails, it does not skip
            pytest.fail("chromium is not installed (apt-get install chromium)")
        to_r, self._write = os.pipe()  # commands: we write, the browser reads on its fd 3
        self._read, from_w = os.pipe()  # answers: the browser writes on its fd 4, we read
        # above 9, so that 3<& and 4>& below cannot overwrite one of them
        r3 = fcntl.fcntl(to_r, fcntl.F_DUPFD_CLOEXEC, 10)
        w4 = fcntl.fcntl(from_w, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(to_r)
        os.close(from_w)
        self._log = log.open("wb")
        self.proc = subprocess.Popen(
            [
                "/bin/bash",  # dash redirects fds 0-9 only
                "-c",
                f'exec "$0" "$@" 3<&{r3} 4>&{w4} {r3}<&- {w4}>&-',
                exe,
                "--headless=new",
                "--no-sandbox",  # root on CI
                "--disable-gpu",
                "--disable-extensions",
                "--disable-background-networking",
                "--no-first-run",
                "--no-default-browser-check",
                "--remote-debugging-pipe",
                f"--user-data-dir={profile}",
                "about:blank",
            ],
            pass_fds=(r3, w4),
            stdin=subprocess.DEVNULL,
            stdout=self._log,
            stderr=subprocess.STDOUT,
            start_new_session=True,  # its own process group: the browser and its helpers
        )
        os.close(r3)
        os.close(w4)
        self._buffer, self._id, self.events = b"", 0, []

    def __enter__(self) -> Chromium:
        return self

    def __exit__(self, *exc) -> None:
        self.stop()

    def call(self, method: str, session: str | None = None, timeout: float = 60, **params):
        self._id += 1
        message = {"id": self._id, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self._write, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            for answer in self._messages(deadline, method):
                if answer.get("id") == self._id:
                    if "error" in answer:
                        raise RuntimeError(f"{method}: {answer['error']}")
                    return answer["result"]
                self.events.append(answer)

    def _messages(self, deadline: float, method: str) -> list[dict]:
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"chromium did not answer {method}")
            if select.select([self._read], [], [], left)[0]:
                chunk = os.read(self._read, 1 << 20)
                if not chunk:
                    raise EOFError(f"chromium exited (code {self.proc.poll()}) during {method}")
                self._buffer += chunk
        *done, self._buffer = self._buffer.split(b"\0")
        return [json.loads(m) for m in done]

    def evaluate(self, session: str, expression: str, timeout: float = 60):
        """The value of a JavaScript expression in the page (a promise is awaited)."""
        r = self.call(
            "Runtime.evaluate",
            session,
            timeout=timeout,
            expression=expression,
            awaitPromise=True,
            returnByValue=True,
        )
        if "exceptionDetails" in r:
            raise AssertionError(f"in the page: {r['exceptionDetails']}")
        return r["result"].get("value")

    def open(self, url: str) -> str:
        """A new tab at ``url``, loaded; its protocol session."""
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        self.call("Runtime.enable", session)
        self.call("Page.navigate", session, url=url)
        deadline = time.monotonic() + 60
        while self.evaluate(session, "document.readyState") != "complete":
            assert time.monotonic() < deadline, f"{url} did not load"
            time.sleep(0.05)
        return session

    def _group_alive(self) -> bool:
        try:
            os.killpg(self.proc.pid, 0)
        except ProcessLookupError:
            return False
        return True

    def stop(self) -> None:
        """Close the browser, and end what is left of the process group it was started in."""
        try:
            self.call("Browser.close", timeout=10)
        except Exception:  # gone already, or not answering: ended below
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass
        deadline = time.monotonic() + 5
        while self._group_alive() and time.monotonic() < deadline:
            time.sleep(0.05)
        if self._group_alive():
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait(timeout=10)
        for fd in (self._write, self._read):
            os.close(fd)
        self._log.close()


# Read the report as a reader does: from the menu's Results section open each category, read
# the files its table lists, open each file's information panel and read its description.
READ_REPORT = """(async () => {
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
  const until = async (find, what) => {
    for (let i = 0; i < 400; i++) {
      const found = find();
      if (found) return found;
      await sleep(25);
    }
    throw new Error("the report never showed " + what);
  };
  const nav = () => document.querySelector("nav");
  const text = (el) => el.textContent.trim();
  const home = async () => {
    if (!menu()) (await until(() => nav().querySelector("ol a"), "its home link")).click();
    return until(menu, "its menu");
  };
  // the menu's items below its "Results" heading (a heading is an item without a link)
  const menu = () => {
    const items = [...nav().querySelectorAll("ul > li")];
    const at = items.findIndex((li) => !li.querySelector("a") && text(li) === "Results");
    return at < 0 ? null : items.slice(at + 1).filter((li) => li.querySelector("a"));
  };
  const rows = () => [...nav().querySelectorAll("tbody tr")];
  const openCategory = async (name) => {
    const item = (await home()).find((li) => text(li) === name);
    item.querySelector("a").click();
    return until(() => rows().length && rows(), "the files of " + name);
  };
  const description = () => {
    const items = [...nav().querySelectorAll("ul > li")];
    const at = items.findIndex((li) => !li.querySelector("a") && text(li) === "Description");
    return at < 0 ? null : items[at + 1];
  };
  await until(() => nav() && menu(), "a menu with a Results section");
  const listed = {};
  for (const category of (await home()).map(text)) {
    listed[category] = {};
    const files = (await openCategory(category)).map((tr) => text(tr.querySelector("td")));
    for (const [i, file] of files.entries()) {
      const row = (await openCategory(category))[i];
      row.querySelector("a[iconname='information-circle']").click();
      listed[category][file] = text(await until(description, "the description of " + file));
    }
  }
  return listed;
})()"""


@pytest.fixture(scope="module")
def report(quick_run, tmp_path_factory) -> tuple[Path, dict]:
    """The quick run's report (made in a copy of the run), as Chromium renders it: the work
    directory and {category: {file: its description}}."""
    work = tmp_path_factory.mktemp("report") / "wf"
    shutil.copytree(quick_run, work, symlinks=True)
    html = work / "report.html"
    p = snakemake(work, "all", "moves", "--report", str(html), *QUICK)  # what the run built
    assert p.returncode == 0, p.stderr[-3000:]
    with Chromium(work.parent / "chromium-profile", work.parent / "chromium.log") as browser:
        session = browser.open(html.as_uri())
        listed = browser.evaluate(session, READ_REPORT, timeout=120)
        thrown = [e for e in browser.events if e.get("method") == "Runtime.exceptionThrown"]
        assert not thrown, f"the report's JavaScript failed: {thrown}"
    return work, listed


def test_report_lists_every_result_of_the_run(report):
    work, listed = report
    expected = {}
    for e in report_entries(work):
        for path in sorted(work.glob(re.sub(r"\{[^}]+\}", "*", e.path))):
            expected[path.relative_to(work).as_posix()] = e
    assert expected, "the quick run made no file its rules mark for the report"
    shown = {
        file: (category, text) for category, files in listed.items() for file, text in files.items()
    }
    missing = sorted(set(expected) - set(shown))
    assert not missing, f"marked for the report, made by the run, not listed: {missing}"
    extra = sorted(set(shown) - set(expected))
    assert not extra, f"listed, but no rule of the run marks it for the report: {extra}"
    for file, e in expected.items():
        category, text = shown[file]
        assert category == e.category, f"{file} under {category}, its rule says {e.category}"
        assert caption_text(text) == caption_text(e.caption.read_text()), f"{file}: {text!r}"


def test_report_lists_every_figure_the_run_drew(report):
    """A figure is a drawing in results/ (its PDF and PNG are one figure): one of its files is
    listed, whatever the rules say."""
    work, listed = report
    shown = {Path(file).with_suffix("") for files in listed.values() for file in files}
    drawn = {
        p.relative_to(work).with_suffix("")
        for p in (work / "results").rglob("*")
        if p.suffix in FIGURE_SUFFIXES
    }
    assert drawn, "the quick run drew no figure"
    unlisted = sorted(str(p) for p in drawn - shown)
    assert not unlisted, f"figures the run drew that the report does not list: {unlisted}"
    assert {"Figures", "Tables"} <= set(listed), sorted(listed)
