#!/usr/bin/env bats
# Hostile world XML through rscene-from-xml (issue 15): entity expansion,
# deep nesting, huge loops, include cycles.  Each one must end in bounded
# time (timeout 10) and memory (ulimit -v 1 GiB) with exit 2, an error
# naming the file and line, and no output: -o leaves no file, and an
# existing -o file is left as it was.

load helpers
FROM="$BIN/rscene-from-xml"

setup() {
  needs_tools rscene-from-xml
  in_workdir
}

# from_xml_refused FILE [ARG...]: refused (helpers.bash) by rscene-from-xml
# FILE ARG... -o out.rscene, with an error in FILE; sets $stderr.
from_xml_refused() {
  local file=$1
  shift
  refused "$file:" "$FROM" "$file" "$@" -o out.rscene
}

@test "billion laughs: a DOCTYPE declaring entities is refused at its line, nothing expanded" {
  awk 'BEGIN {
    print "<?xml version=\"1.0\"?>"; print "<!DOCTYPE raisim ["; print " <!ENTITY lol \"lol\">"
    for (i = 1; i <= 9; ++i) {
      prev = i == 1 ? "lol" : "lol" (i - 1); s = ""
      for (k = 0; k < 10; ++k) s = s "&" prev ";"
      print " <!ENTITY lol" i " \"" s "\">"
    }
    print "]>"; print "<raisim version=\"1.0\"><objects>"
    print "<sphere name=\"&lol9;\" mass=\"1\"><dim radius=\"1\"/><state pos=\"0 0 1\"/></sphere>"
    print "</objects></raisim>" }' >laughs.xml
  from_xml_refused laughs.xml
  [[ ${stderr} =~ laughs\.xml:[0-9]+:[0-9]+:\ error:\ .*[Ee]ntit.*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
  [ "$(wc -l <<<"$stderr")" -lt 20 ]
}

@test "an undeclared entity (&lol;) is an error too, not text" {
  printf '<raisim version="1.0"><objects>\n<sphere name="a&lol;" mass="1"><dim radius="1"/><state pos="0 0 1"/></sphere>\n</objects></raisim>\n' >undeclared.xml
  from_xml_refused undeclared.xml
  [[ ${stderr} =~ undeclared\.xml:2:[0-9]+:\ error:\ .*lol.*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
}

@test "10^5-deep nesting is refused at the first element past the depth limit" {
  awk 'BEGIN {
    print "<raisim version=\"1.0\">"; print "<objects>"
    for (i = 0; i < 100000; ++i) print "<compound>"
    for (i = 0; i < 100000; ++i) print "</compound>"
    print "</objects>"; print "</raisim>" }' >deep.xml
  from_xml_refused deep.xml
  [[ ${stderr} =~ deep\.xml:[0-9]+:[0-9]+:\ error:\ .*(deep|depth|nest).*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
  line=$(sed -n 's/^deep\.xml:\([0-9]*\):.*/\1/p' <<<"$stderr" | head -1)
  # Refused where the nesting passes the limit (64 after expansion; tinyxml2's own is 500), not at the end.
  [ "$line" -gt 3 ] && [ "$line" -lt 1000 ]
}

@test "an array of 10^9 iterations is refused before it runs, at the array's line" {
  cat >loop.xml <<'EOF'
<raisim version="1.0">
  <objects>
    <array idx="@@i" start="0" end="1000000000" increment="1">
      <sphere name="s@@i" mass="1"><dim radius="0.1"/><state pos="0 0 {@@i}"/></sphere>
    </array>
  </objects>
</raisim>
EOF
  from_xml_refused loop.xml
  [[ ${stderr} =~ loop\.xml:3:[0-9]+:\ error:\ .*array.*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
  # A parameter can make it so too: the same with end="@@n" and --param n=1000000000.
  sed 's/end="1000000000"/end="@@n"/' loop.xml >param.xml
  from_xml_refused param.xml --param n=1000000000
  [[ ${stderr} =~ param\.xml:3:[0-9]+:\ error: ]] || { echo "$stderr"; false; }
}

@test "nested arrays of 1000 x 1000 x 1000 iterations are refused: the limit counts all iterations" {
  cat >nested.xml <<'EOF'
<raisim version="1.0">
  <objects>
    <array idx="@@i" start="0" end="1000" increment="1">
      <array idx="@@j" start="0" end="1000" increment="1">
        <array idx="@@k" start="0" end="1000" increment="1">
          <sphere name="s@@i_@@j_@@k" mass="1"><dim radius="0.1"/><state pos="@@i @@j @@k"/></sphere>
        </array>
      </array>
    </array>
  </objects>
</raisim>
EOF
  from_xml_refused nested.xml
  [[ ${stderr} =~ nested\.xml:[3-5]:[0-9]+:\ error:\ .*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
}

@test "an include cycle (a -> b -> a) is refused naming the include's file and line" {
  cat >a.xml <<'EOF'
<raisim version="1.0">
  <include file="[THIS_DIR]/b.xml"/>
  <objects/>
</raisim>
EOF
  cat >b.xml <<'EOF'
<raisim version="1.0">
  <gravity value="0 0 -9.81"/>
  <include file="[THIS_DIR]/a.xml"/>
</raisim>
EOF
  refused "" "$FROM" a.xml -o out.rscene  # the error may be in b.xml
  # At the include that would read a file a second time (a.xml's line 2,
  # reached again through b.xml), or at b.xml's include that closes it.
  [[ ${stderr} =~ (a\.xml:2|b\.xml:3):[0-9]+:\ error:\ .*cycle.*b\.xml.*a\.xml.*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
  # A file that includes itself: the same.
  printf '<raisim version="1.0">\n<include file="self.xml"/>\n</raisim>\n' >self.xml
  from_xml_refused self.xml
  [[ ${stderr} =~ self\.xml:2:[0-9]+:\ error: ]] || { echo "$stderr"; false; }
}

@test "an expression nested 10^5 parentheses deep is refused, not a stack overflow" {
  {
    printf '<raisim version="1.0"><objects>\n<sphere name="s" mass="1"><dim radius="{'
    awk 'BEGIN { for (i = 0; i < 100000; ++i) printf "("; printf "1"; for (i = 0; i < 100000; ++i) printf ")" }'
    printf '}"/><state pos="0 0 1"/></sphere>\n</objects></raisim>\n'
  } >parens.xml
  from_xml_refused parens.xml
  [[ ${stderr} =~ parens\.xml:2:[0-9]+:\ error:\ .*\[RS81[0-9][0-9]\] ]] || { echo "$stderr"; false; }
}

@test "a 100 MiB world is refused before it is read whole: as a file and on standard input" {
  # The 64 MiB per-file limit held for included files only: the top file
  # and standard input were read in full (exit 0, 930 MB).  ulimit -v 1 GiB
  # in refused and 200 MB here keep the read bounded.
  { printf '<raisim><!--'; head -c 104857600 /dev/zero | tr '\0' x; printf '%s\n' '--></raisim>'; } >big.xml
  from_xml_refused big.xml
  [[ $stderr == "big.xml: error: cannot read: file larger than 67108864 bytes [RS8101]" ]]
  run -2 --separate-stderr bash -c 'ulimit -v 204800; exec timeout 10 "$@" <big.xml' _ "$FROM" - --stdin-filename in.xml
  [[ $stderr == "in.xml: error: cannot read: file larger than 67108864 bytes [RS8101]" ]]
  [ -z "$output" ]
  run -2 --separate-stderr bash -c 'ulimit -v 204800; cat big.xml | exec timeout 10 "$@"' _ "$FROM"
  [[ $stderr == "<stdin>: error: cannot read: file larger than 67108864 bytes [RS8101]" ]]
}

@test "a mismatched end tag names both elements at the end tag's line and column" {
  printf '<raisim>\n  <objects>\n    <sphere name="a">\n  </objects>\n</raisim>\n' >nw.xml
  from_xml_refused nw.xml
  [[ $stderr == "nw.xml:4:3: error: not well-formed XML: </objects> closes <sphere> opened at 3:5 [RS8101]"* ]]
  printf '<raisim>\n<sphere name="a" mass="1" name="b"/>\n</raisim>\n' >dup.xml
  from_xml_refused dup.xml
  [[ $stderr == "dup.xml:2:27: error: not well-formed XML: attribute 'name' written twice (first at 2:9) [RS8101]"* ]]
}

@test "character references XML 1.0 forbids (&#0;, &#x1;, surrogates) are refused at their column" {
  printf '<raisim>\n<objects>\n<sphere name="a&#0;b"/>\n</objects>\n</raisim>\n' >nul.xml
  from_xml_refused nul.xml
  [[ $stderr == "nul.xml:3:16: error: &#0; is a character XML 1.0 forbids"*"[RS8102]"* ]]
  printf '<raisim>\n<objects>\n<sphere name="&#x1;"/><box name="&#xD800;"/>\n</objects>\n</raisim>\n' >ctl.xml
  from_xml_refused ctl.xml
  [[ $stderr == *"ctl.xml:3:15: error: &#x1; is a character"* ]]
  [[ $stderr == *"ctl.xml:3:34: error: &#xD800; is a character"* ]]
}
