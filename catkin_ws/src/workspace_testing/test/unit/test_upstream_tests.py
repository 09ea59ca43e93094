"""workspace_testing.upstream_tests: upstream files read from a work tree and from a git mirror alike, the scratch
package's package.xml and CMakeLists (catkin parses them), and rostest's JUnit results read back."""
from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "src"))

from workspace_testing.upstream_tests import (  # noqa: E402
    GTest,
    ScratchPackage,
    UpstreamSource,
    find_upstream,
    read_results,
    shell_command,
)


@pytest.fixture()
def upstream(tmp_path: Path) -> Path:
    """A repository with pkg/test/a.test, an executable pkg/scripts/run.py and a file outside: committed."""
    tree = tmp_path / "tree"
    (tree / "pkg" / "test").mkdir(parents=True)
    (tree / "pkg" / "scripts").mkdir()
    (tree / "pkg" / "test" / "a.test").write_text("<launch/>\n")
    (tree / "pkg" / "scripts" / "run.py").write_text("#!/usr/bin/env python3\n")
    (tree / "pkg" / "scripts" / "run.py").chmod(0o755)
    (tree / "other.txt").write_text("not in pkg\n")
    git = ["git", "-C", str(tree), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run(git[:3] + ["init", "-q"], check=True)
    subprocess.run(git + ["add", "."], check=True)
    subprocess.run(git + ["commit", "-q", "-m", "files"], check=True)
    return tree


def test_a_work_tree_and_its_git_directory_give_the_same_files(upstream: Path) -> None:
    from_tree = UpstreamSource(str(upstream)).files_under("pkg/test")
    mirror = upstream.parent / "mirror.git"
    subprocess.run(["git", "clone", "-q", "--mirror", str(upstream), str(mirror)], check=True)
    from_git = UpstreamSource(str(mirror)).files_under("pkg/scripts")
    assert set(from_tree) == {"pkg/test/a.test"} and from_tree["pkg/test/a.test"].data == b"<launch/>\n"
    assert set(from_git) == {"pkg/scripts/run.py"} and from_git["pkg/scripts/run.py"].executable


def test_no_repository_is_said_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("UPSTREAM_TEST_REPO", raising=False)
    cache = str(tmp_path / "cache")
    source, why = find_upstream("UPSTREAM_TEST_REPO", str(tmp_path / "nowhere"), cache, "HEAD")
    assert source is None and "$UPSTREAM_TEST_REPO is not set" in why
    # what is missing and how to provide it, in one line alike for every test of the repository (summarized once)
    assert "set UPSTREAM_TEST_REPO to a checkout or git mirror" in why and cache in why and "\n" not in why
    assert find_upstream("UPSTREAM_TEST_REPO", str(tmp_path / "nowhere"), cache, "HEAD") == (None, why)
    with pytest.raises(FileNotFoundError):
        UpstreamSource(str(tmp_path / "nowhere"))


def test_a_half_made_mirror_is_no_source(upstream: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # what `git clone --mirror` has written before it fetches: HEAD and objects/, no refs (CI once found one, left
    # by a run stopped mid-clone, and failed on it instead of skipping)
    monkeypatch.delenv("UPSTREAM_TEST_REPO", raising=False)
    cache = tmp_path / "cache.git"
    subprocess.run(["git", "init", "-q", "--bare", str(cache)], check=True)
    source, why = find_upstream("UPSTREAM_TEST_REPO", str(upstream), str(cache), "HEAD")
    assert source is None and f"{cache} has no commit HEAD" in why and "\n" not in why
    subprocess.run(["git", "--git-dir", str(cache), "fetch", "-q", str(upstream), "HEAD:refs/heads/main"], check=True)
    subprocess.run(["git", "--git-dir", str(cache), "symbolic-ref", "HEAD", "refs/heads/main"], check=True)
    source, _ = find_upstream("UPSTREAM_TEST_REPO", str(upstream), str(cache), "HEAD")
    assert source is not None and set(source.files_under("pkg/test")) == {"pkg/test/a.test"}


def test_the_scratch_package_holds_upstreams_files_and_its_own_build(upstream: Path, tmp_path: Path) -> None:
    files = UpstreamSource(str(upstream)).files_under("pkg")
    gtest = GTest("a-test", "test/a.test", ("test/a.cpp",), ("${OpenCV_LIBRARIES}",))
    package = ScratchPackage("gazebo_plugins", ("roscpp", "image_transport"), ("core", "calib3d"), (gtest,))
    folder = tmp_path / "src" / "gazebo_plugins"
    package.write(str(folder), files, "pkg")
    assert (folder / "test" / "a.test").read_text() == "<launch/>\n"
    assert (folder / "scripts" / "run.py").stat().st_mode & 0o111
    cmake = (folder / "CMakeLists.txt").read_text()
    assert "find_package(catkin REQUIRED COMPONENTS roscpp image_transport)" in cmake
    assert "find_package(OpenCV REQUIRED COMPONENTS core calib3d)" in cmake
    assert "add_rostest_gtest(a-test test/a.test test/a.cpp)" in cmake
    assert "target_link_libraries(a-test ${catkin_LIBRARIES} ${OpenCV_LIBRARIES})" in cmake
    manifest = ElementTree.parse(str(folder / "package.xml")).getroot()
    assert manifest.findtext("name") == "gazebo_plugins"
    assert [depend.text for depend in manifest.findall("depend")] == ["roscpp", "image_transport"]


def test_results_count_cases_run_and_name_the_failed_and_skipped(tmp_path: Path) -> None:
    (tmp_path / "rostest-a.xml").write_text(
        '<testsuite><testcase classname="x.T" name="ok"/>'
        '<testcase classname="x.T" name="bad"><failure message="boom">trace</failure></testcase></testsuite>'
    )
    (tmp_path / "inner").mkdir()
    (tmp_path / "inner" / "b.xml").write_text(
        '<testsuites><testsuite><testcase classname="y" name="e">'
        '<error message="crash"/></testcase></testsuite></testsuites>'
    )
    (tmp_path / "c.xml").write_text(
        '<testsuite><testcase classname="z" name="s"><skipped message="not here"/></testcase>'
        '<testcase classname="z" name="g" status="run" result="skipped"/></testsuite>'
    )
    results = read_results(str(tmp_path))
    assert results.tests == 3  # the skipped cases did not run
    assert sorted(results.failed) == ["b.xml: y.e: crash", "rostest-a.xml: x.T.bad: boomtrace"]
    assert results.skipped == ["c.xml: z.s: not here", "c.xml: z.g: skipped"]


def test_the_shell_command_quotes_its_words() -> None:
    command = shell_command("/ws/devel/setup.bash", ["echo", "it's", "a b"])
    assert (
        subprocess.run(
            ["bash", "-c", command[2].replace(". '/ws/devel/setup.bash' && ", "")], capture_output=True, text=True
        ).stdout
        == "it's a b\n"
    )
