# fish completion for rscene-from-json
complete -c rscene-from-json -s h -l help -d 'Print help and exit'
complete -c rscene-from-json -l version -d 'Print version and exit'
complete -c rscene-from-json -s o -l output -r -F -d 'Write the scene to FILE atomically'
complete -c rscene-from-json -l stdin-filename -r -F -d 'Name standard input in messages'
complete -c rscene-from-json -k -x -a '(__fish_complete_suffix .json)'
