# fish completion for rscene-fmt
complete -c rscene-fmt -s h -l help -d 'Print help and exit'
complete -c rscene-fmt -l version -d 'Print version and exit'
complete -c rscene-fmt -s o -l output -r -F -d 'Write the result to FILE atomically'
complete -c rscene-fmt -s i -l in-place -d 'Rewrite each file in place'
complete -c rscene-fmt -l check -d 'List files that are not canonical, exit 1 if any'
complete -c rscene-fmt -l diff -d 'Print a unified diff of what would change'
complete -c rscene-fmt -l stdin-filename -r -F -d 'Name standard input in messages'
complete -c rscene-fmt -k -x -a '(__fish_complete_suffix .rscene)'
