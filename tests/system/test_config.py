"""The config file (--config): a line is read whole, whatever its length, and a value too long
for its setting is refused, not cut.

The reader used to take lines in pieces of 4199 bytes: the rest of a long comment was then
read as a line of its own, and taken as a setting when it looked like one. And a value
longer than its field (a token of 128 bytes or more, a path of PATH_MAX) was cut short
without a word, so the daemon ran with another token or path than the one written.
"""
import pytest

from daemon import Daemon, DaemonError


def start_with(tmp_path, text):
    conf = tmp_path / "postured.conf"
    conf.write_text(text)
    d = Daemon(extra=("--config", str(conf)))
    d.start()
    return d


def test_the_rest_of_a_long_comment_is_no_setting(tmp_path):
    init = tmp_path / "first.init"
    init.write_text("load human as sneaked\n")
    # the comment's first 4199 bytes, then what a reader of pieces took for a line
    comment = "#" + "x" * 4198 + f"init = {init}\n"
    d = start_with(tmp_path, "fps = 60\n" + comment + "# the end\n")
    try:
        with d.client() as c:
            assert c.request("list figures")["figures"] == []
    finally:
        d.stop()
        d.cleanup()


def test_a_long_line_is_one_setting(tmp_path):
    init = tmp_path / "first.init"
    init.write_text("load human as jack\n")
    # 5000 blanks between the key and its '=': one line, read whole
    d = start_with(tmp_path, "init" + " " * 5000 + f"= {init}\n")
    try:
        with d.client() as c:
            assert [f["name"] for f in c.request("list figures")["figures"]] == ["jack"]
    finally:
        d.stop()
        d.cleanup()


@pytest.mark.parametrize("line, says", [
    ("token = " + "t" * 128, "token is longer than 127 bytes"),
    ("frames = /" + "f" * 5000, "frames is longer than 4095 bytes"),
    ("fps = 60\0garbage", "a NUL byte"),
])
def test_a_value_too_long_or_a_nul_byte_is_refused_with_its_line(tmp_path, line, says):
    conf = tmp_path / "postured.conf"
    conf.write_text("# settings\nfps = 60\n" + line + "\n")
    d = Daemon(extra=("--config", str(conf)))
    try:
        with pytest.raises(DaemonError) as e:
            d.start()
        assert says in str(e.value) and f"{conf}:3" in str(e.value), str(e.value)
    finally:
        d.cleanup()


def test_a_flag_too_long_is_refused(tmp_path):
    d = Daemon(extra=("--token", "t" * 200))
    try:
        with pytest.raises(DaemonError) as e:
            d.start()
        assert "token is longer than 127 bytes" in str(e.value)
    finally:
        d.cleanup()
