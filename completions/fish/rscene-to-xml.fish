# fish completion for rscene-to-xml
complete -c rscene-to-xml -s h -l help -d 'Print help and exit'
complete -c rscene-to-xml -l version -d 'Print version and exit'
complete -c rscene-to-xml -s o -l output -r -F -d 'Write the XML to FILE atomically'
complete -c rscene-to-xml -l stdin-filename -r -F -d 'Name standard input in messages and for asset paths'
complete -c rscene-to-xml -l absolute-paths -d 'Write asset paths absolute instead of [THIS_DIR]/relative'
complete -c rscene-to-xml -s q -l quiet -d 'Do not list what the XML cannot hold'
complete -c rscene-to-xml -k -x -a '(__fish_complete_suffix .rscene)'
complete -c rscene-to-xml -l relative-to -r -a '(__fish_complete_directories)' -d 'Standard output only: write asset paths relative to DIR'
