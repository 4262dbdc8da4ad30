# size-report.awk - flash and RAM per module of the firmware image, from the linker's map
# file (what really went into the image, after --gc-sections), against the budgets.
#   awk -f size-report.awk fbrl-cm3.map
# Flash = code, read-only data and the initial values of .data/.tdata; RAM = .data,
# .tdata, .tbss, .bss and the stack.
BEGIN { FLASH_BUDGET = 128 * 1024; RAM_BUDGET = 64 * 1024; inmap = 0 }
/^Linker script and memory map/ { inmap = 1; next }
!inmap { next }
# An output section: remember where its input sections go, and its exact size (the
# per-module figures count merged strings before merging, so their sum is a little high).
/^\.[A-Za-z_]/ {
    out = $1
    if ($3 ~ /^0x/) osize[out] = strtonum_hex($3)
    next
}
# An input section whose name was too long: its address, size and file are on the next line.
/^ [.A-Z][^ ]*$/ { pending = 1; next }
/^ [.A-Z]/ || (pending && /^  +0x/) {
    n = split($0, f, /[ \t]+/)
    # fields: "" name addr size file   or (continued line) "" addr size file
    if (pending) { addr = f[2]; size = f[3]; file = f[4] } else { addr = f[3]; size = f[4]; file = f[5] }
    pending = 0
    if (size !~ /^0x/ || file == "") next
    bytes = strtonum_hex(size)
    if (bytes == 0) next
    mod = module(file)
    if (out == ".text") flash[mod] += bytes
    else if (out == ".data" || out == ".tdata") { flash[mod] += bytes; ram[mod] += bytes }
    else if (out == ".bss" || out == ".tbss") ram[mod] += bytes
    mods[mod] = 1
    next
}
function strtonum_hex(s,    v, i, c) {
    v = 0; s = tolower(s); sub(/^0x/, "", s)
    for (i = 1; i <= length(s); i++) { c = index("0123456789abcdef", substr(s, i, 1)) - 1; v = v * 16 + c }
    return v
}
function module(file,    m) {
    if (file ~ /lib(c|m)\.a\(/ ) return "C library (picolibc)"
    if (file ~ /libgcc\.a\(/) return "compiler runtime (libgcc)"
    m = file; sub(/.*\//, "", m); sub(/\.o$/, "", m)
    return m
}
END {
    ram["main stack"] += osize[".stack"]; mods["main stack"] = 1
    printf "%-28s %8s %8s\n", "module", "flash", "RAM"
    cmd = "sort -t'|' -k2,2nr | awk -F'|' '{ printf \"%-28s %8d %8d\\n\", $1, $2, $3 }'"
    for (m in mods) { printf "%s|%d|%d\n", m, flash[m], ram[m] | cmd; tf += flash[m]; tr += ram[m] }
    close(cmd)
    printf "%-28s %8d %8d\n", "sum of the modules", tf, tr
    imgf = osize[".text"] + osize[".data"] + osize[".tdata"]
    imgr = osize[".data"] + osize[".tdata"] + osize[".tbss_space"] + osize[".bss"] + osize[".stack"]
    printf "%-28s %8d %8d\n", "image (exact)", imgf, imgr
    printf "%-28s %8d %8d\n", "budget", FLASH_BUDGET, RAM_BUDGET
    printf "flash %.1f %% of its budget (%s), RAM %.1f %% of its budget (%s)\n", 100 * imgf / FLASH_BUDGET,
        imgf <= FLASH_BUDGET ? "within" : "OVER", 100 * imgr / RAM_BUDGET, imgr <= RAM_BUDGET ? "within" : "OVER"
}
