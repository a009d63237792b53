# Sourced by the tests that run a README block as written (readme_using_it.sh,
# readme_machine_loop.sh), after `root=` (the source tree):
#   readme_block HEADING [FROM TO]...  prints the first ```sh block under the
#       README's HEADING, each FROM replaced by TO (a FROM missing from the
#       block fails: the README changed under the test)
#   readme_workdir DIR HEXCAL  makes DIR with build/app/hexcal, a link to
#       HEXCAL, and scripts/, a link to the tree's: the block's paths as a
#       user at the top of a checkout types them, with nothing else there
readme_block() {
  python3 - "$root/README.md" "$@" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
heading, pairs = sys.argv[2], sys.argv[3:]
assert "\n" + heading + "\n" in text, "README.md has no section " + heading
section = text.split("\n" + heading + "\n", 1)[1]
block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
for old, new in zip(pairs[::2], pairs[1::2]):
    assert old in block, old + " is not in the README's block under " + heading
    block = block.replace(old, new)
print(block, end="")
PY
}

readme_workdir() {
  mkdir -p "$1/build/app"
  ln -s "$2" "$1/build/app/hexcal"
  ln -s "$root/scripts" "$1/scripts"
}
